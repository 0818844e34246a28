import math, numpy as np
from rockjoint import meshes
from rockjoint.meshes.slope import SlopeGeometry, slope_section
g = SlopeGeometry(height=30.0, face_angle=60.0, base=20.0, toe_distance=30.0, crest_distance=40.0)
toe = g.toe
xc = g.crest[0] + 6.0
plane = meshes.Joint(point=toe, dip=35.0, dip_direction=270.0, name="plane", bounded_by=("crack",))
crack = meshes.Joint(point=(xc, g.base + g.height - 1.0), dip=90.0, dip_direction=90.0, name="crack", bounded_by=("plane",))
jm = slope_section(g, [plane, crack], mesh_size=3.0, joint_mesh_size=1.0)
print(jm.names["blocks"], jm.names["joints"], jm.names["boundaries"], jm.points.shape if hasattr(jm, "points") else "")
