"""rockjoint.meshes: gmsh builders of rock blocks cut by joints (sources live in meshes/)."""
