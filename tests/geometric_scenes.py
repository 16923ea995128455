"""The settings the geometric multilevel tests share (geometric_three_levels,
geometric_coarsest_solve): the solvers compared, and the two scenes that take
each hierarchy path — the 3D plastic F-bar block of 8^3 equal cells (the box
path: 4^3 and 2^3 below) and two J2 bodies with a gap in 3D (with
Geometry/Global refinements = 2: the grandparents' vertices)."""

DIRECT = ["Mechanics/Linear solver/Type=direct"]
GEOMETRIC = ["Mechanics/Linear solver/Type=iterative", "Mechanics/Linear solver/Preconditioner=geometric"]
PER_BODY = ["Geometry/Partition=per body"]
BLOCK = ["Mechanics/Element=F-bar", "Bodies/body/Material/Model=J2",
         "Bodies/body/Material/Hardening/Initial yield stress=300",
         "Bodies/body/Material/Hardening/Hardening modulus=1000", "Dimension=3",
         "Boundary conditions/Displacement=front: ux = 0, uy = 0, uz = 0; back: uz = -0.05*t",
         "Geometry/Blocks=body: 0, 0, 0, 1, 1, 1, 8, 8, 8"]
TWICE = ["Geometry/Global refinements=2"]
THREE_D = ["Dimension=3",
           "Geometry/Blocks=a: 0, 0, 0, 1, 1, 1, 2, 2, 2; b: 1.5, 0, 0, 2.5, 0.5, 1, 2, 1, 2",
           "Boundary conditions/Displacement=a.bottom: ux = 0, uy = 0, uz = 0; a.top: uy = -0.01*t; "
           "b.bottom: ux = 0, uy = 0, uz = 0; b.top: ux = 0.003*t, uy = -0.006*t, uz = 0.002*t"]
