# Yade's cohesive-frictional bonded model on the same beam, for the benchmark
# (benchmark.py runs this with `yade -j1 -n -x yadeBondedBeam.py PACKING STEPS DT OUT`).
# Same packing, time step, end pads, platen (a 48-facet cylinder moving at the
# same speed), bond criterion (distFactor 1.1) and local damping 0.1.
import json
import math
import sys
import time

from yade import geom

packing, steps, dt, out = sys.argv[1], int(sys.argv[2]), float(sys.argv[3]), sys.argv[4]
E, rho, breakN, beta, mu = 5.4e8, 917.0, 0.0037, 1.25, 0.3
length, width, thickness, pad, platen_d, speed = 2.9, 0.5, 0.55, 0.2, 0.15, 0.1

ice = O.materials.append(CohFrictMat(
    young=E, poisson=1.0 / 2.6, density=rho, frictionAngle=math.atan(mu),
    normalCohesion=breakN * E, shearCohesion=beta * breakN * E,
    isCohesive=True, momentRotationLaw=True, etaRoll=0.05, etaTwist=0.05))
steel = O.materials.append(CohFrictMat(young=2e11, poisson=0.3, density=7800,
                                       frictionAngle=math.atan(mu), isCohesive=False))

rows = []
with open(packing) as f:
    in_atoms = False
    for line in f:
        parts = line.split()
        if parts[:1] == ["Atoms"]:
            in_atoms = True
            continue
        if in_atoms and len(parts) == 7:
            rows.append(parts)
for tag, kind, diameter, density, x, y, z in rows:
    b = O.bodies.append(sphere((float(x), float(y), float(z)), 0.5 * float(diameter), material=ice))
    if kind == "2":
        O.bodies[b].state.blockedDOFs = "xyzXYZ"

r = 0.5 * platen_d
facets = geom.facetCylinder((0.5 * length, -r - 0.002, 0.5 * thickness), r, thickness + 0.04,
                            segmentsNumber=48, wallMask=4, material=steel, fixed=True)
platen_ids = O.bodies.append(facets)

O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(aabbEnlargeFactor=1.1), Bo1_Facet_Aabb()]),
    InteractionLoop(
        [Ig2_Sphere_Sphere_ScGeom6D(interactionDetectionFactor=1.1), Ig2_Facet_Sphere_ScGeom6D()],
        [Ip2_CohFrictMat_CohFrictMat_CohFrictPhys(setCohesionNow=True, setCohesionOnNewContacts=False)],
        [Law2_ScGeom6D_CohFrictPhys_CohesionMoment(useIncrementalForm=True, always_use_moment_law=True)]),
    TranslationEngine(ids=platen_ids, translationAxis=(0, 1, 0), velocity=speed),
    NewtonIntegrator(damping=0.1),
]
O.dt = dt
O.run(1, True)   # creates the bonds
for bo in O.engines[1].boundDispatcher.functors:
    if hasattr(bo, "aabbEnlargeFactor"):
        bo.aabbEnlargeFactor = -1
O.engines[2].geomDispatcher.functors[0].interactionDetectionFactor = -1
bonds = sum(1 for i in O.interactions if i.isReal and isinstance(i.phys, CohFrictPhys) and i.phys.cohesionBroken is False)

start = time.time()
O.run(steps, True)
wall = time.time() - start
spheres = len(rows)
result = {"code": "yade", "version": version, "particles": spheres, "bonds": bonds, "steps": steps,
          "dt": dt, "loop_wall_s": wall, "particle_steps_per_s": spheres * steps / wall}
with open(out, "w") as f:
    json.dump(result, f, indent=2)
print(json.dumps(result))
