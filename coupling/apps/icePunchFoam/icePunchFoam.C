/*---------------------------------------------------------------------------*\
Application
    icePunchFoam

Description
    The loading stage of the ridge scenes (rubble punch; cases/rubblePunch,
    ./Allrun -water cfd) at the cfd water level: the assembled ridge
    (DEM/ridge.h5, from ridgeDEM -stage assemble) is loaded by the platen of
    demModels' RidgeScene and PlatenLoading, as ridgeDEM does in hydrostatic
    water, while OpenFOAM solves the water around the ice as iceFoam does
    (unresolved CFD-DEM, "model A", PISO on p_rgh, laminar; coupling/README.md):
    drag, -V grad(p) (buoyancy and dynamic pressure) and the fluid fraction
    come from the coupling.

    The fluid mesh ends at the still water surface where the ridge floats
    (waterSurface: particles crossing it get the share of their submerged
    cap). The surface does not move (no VOF): neither the ice pushed under nor
    the platen raises the water. The platen is a DEM mesh wall only: its own
    displacement of water is not modelled, as at the hydrostatic level.

    One coupling step, as in iceFoam: the fluid crosses the coupling time with
    the exchange made at its start; the particles get the same momentum and
    the new pressure gradient; LIGGGHTS crosses it (with the platen, bonds,
    contacts); the particles are located and the exchange updated. The
    loading loop advances in whole coupling steps (force samples rounded to
    them).

    Input: constant/couplingProperties (waterLevel cfd; sub-dictionary cfd:
    the coupling's models, couplingInterval in DEM steps), constant/
    transportProperties, constant/g, 0/U, 0/p_rgh, system/controlDict
    (OpenFOAM's: deltaT is the largest fluid step, the fluid steps divide
    the coupling time), system/loadingDict (the loading control that
    system/controlDict holds for ridgeDEM), constant/ridgeProperties,
    constant/iceProperties, constant/freezeBondProperties, DEM/in.ridge,
    DEM/ridge.h5.
    Output: as ridgeDEM's loading stage (postProcessing/platenForce.csv with
    the fluid's force columns, breakage, summary.json, VTK/), and the fluid
    fields in the time directories.
\*---------------------------------------------------------------------------*/

#include "fvCFD.H"
#include "pisoControl.H"
#include "particleFluidCoupling.H"
#include "couplingInterval.H"
#include "LiggghtsInstance.H"
#include "DemCoupling.H"
#include "FpeTrapsOff.H"
#include "MpiForSerialRun.H"
#include "demModelsAction.H"
#include "RidgeScene.H"

#include <mpi.h>

#include <chrono>
#include <cmath>
#include <memory>

using namespace Foam::iceCoupling;
using ::iceCoupling::demModelsAction;


int main(int argc, char *argv[])
{
    argList::addNote
    (
        "Loading stage of the rubble punch with the water solved by OpenFOAM (cfd level)"
    );
    argList::noFunctionObjects();
    #include "setRootCaseLists.H"
    #include "createTime.H"
    {
        const fileName meshDir(runTime.path()/runTime.constant()/polyMesh::meshSubDir);
        if (!isFile(meshDir/"points") && !isFile(meshDir/"points.gz"))
        {
            FatalErrorInFunction
                << "no fluid mesh: " << meshDir << "/points is missing. The cfd level needs a mesh"
                << " of the water that ends at its surface: run blockMesh (system/blockMeshDict)"
                << (Pstream::parRun() ? ", then decomposePar" : "") << exit(FatalError);
        }
    }
    #include "createMesh.H"

    ::iceCoupling::MpiForSerialRun mpi;
    pisoControl piso(mesh);

    #include "createFields.H"

    if (runTime.controlDict().getOrDefault("adjustTimeStep", false))
    {
        FatalIOErrorInFunction(runTime.controlDict())
            << "entry 'adjustTimeStep': must be off; the fluid advances each coupling"
            << " time in a fixed whole number of steps" << exit(FatalIOError);
    }
    const label couplingSteps = cfdProperties.get<label>("couplingInterval");
    if (couplingSteps < 1)
    {
        FatalIOErrorInFunction(cfdProperties)
            << "entry 'couplingInterval' is " << couplingSteps << ": it is the number of DEM steps"
            << " per coupling step, a whole number >= 1" << exit(FatalIOError);
    }
    const scalar largestFluidStep = runTime.deltaTValue();
    const fileName caseDir(runTime.globalPath());

    iceDEM::RidgeSettings settings;
    demModelsAction([&]() { settings = iceDEM::RidgeSettings::readCase(caseDir, "system/loadingDict"); });
    settings.stage = "load";

    const auto wallStart = std::chrono::steady_clock::now();
    std::unique_ptr<::iceCoupling::DemCoupling> dem;
    std::unique_ptr<couplingInterval> interval;
    std::unique_ptr<particleFluidCoupling> couplingPtr;
    std::vector<::iceCoupling::CouplingParticle> particles;

    iceDEM::ExternalWater water;
    water.density = rho.value();
    water.stepsPerAdvance = couplingSteps;

    // Where RidgeScene would put its hydrostatic water: the coupling's fix,
    // before the bonds' fix. The DEM time step is known from here on.
    water.defineForceFix = [&](iceDEM::LiggghtsInstance& lmp, double surfaceLevel)
    {
        lmp.command("fix cfdCoupling all external pf/callback 1 1");
        dem.reset(new ::iceCoupling::DemCoupling(lmp, "cfdCoupling"));

        const scalar couplingTime = couplingSteps*lmp.timeStep();
        const label fluidSteps = max(label(1), label(std::ceil(couplingTime/largestFluidStep - 1e-9)));
        runTime.setDeltaT(couplingTime/fluidSteps);
        interval.reset(new couplingInterval(cfdProperties, lmp.timeStep(), runTime.deltaTValue()));

        const scalar sampleSteps = settings.loading.sampleInterval/(settings.loading.speed*lmp.timeStep());
        if (couplingSteps > 1.5*sampleSteps)
        {
            FatalIOErrorInFunction(cfdProperties)
                << "entry 'couplingInterval': " << couplingSteps << " DEM steps of " << lmp.timeStep()
                << " s move the platen " << couplingSteps*lmp.timeStep()*settings.loading.speed*1e3
                << " mm, more than the force's sampleInterval " << settings.loading.sampleInterval*1e3
                << " mm (system/loadingDict): the force is sampled after whole coupling steps;"
                << " use at most " << label(1.5*sampleSteps) << " DEM steps (one and a half samples)"
                << exit(FatalIOError);
        }

        const scalar meshTop = mesh.bounds().max().z();
        if (mag(meshTop - surfaceLevel) > 1e-6)
        {
            FatalErrorInFunction
                << "the fluid mesh's top is at z = " << meshTop << " m (system/blockMeshDict), the"
                << " water surface where the assembled ridge floats at z = " << surfaceLevel
                << " m (DEM/ridge.h5; postProcessing/geometry.json waterLevel): the mesh must end"
                << " at the surface" << exit(FatalError);
        }
        // As a token: dictionary::set would print the value to 6 digits.
        dictionary withSurface(cfdProperties);
        withSurface.add(new primitiveEntry("waterLevel", token(meshTop)), true);
        couplingPtr.reset(new particleFluidCoupling(mesh, withSurface, rho.value(), nu.value(), interval->time()));

        Info<< "Coupling every " << interval->demSteps() << " DEM steps (" << interval->time()
            << " s): " << interval->fluidSteps() << " fluid step(s) of " << runTime.deltaTValue()
            << " s; water surface z = " << meshTop << " m" << nl << endl;
    };

    bool exchangeStarted = false;
    water.advance = [&](long steps)
    {
        if (steps % couplingSteps != 0)
        {
            FatalErrorInFunction << "asked for " << steps << " DEM steps, not a whole number of coupling"
                << " steps of " << couplingSteps << abort(FatalError);
        }
        particleFluidCoupling& coupling = *couplingPtr;
        if (!exchangeStarted)
        {
            // LIGGGHTS is set up and the ridge restored: the first exchange.
            particles = dem->gatherAll();
            coupling.updateFluidFraction(particles);
            coupling.updateExchange(particles, U);
            alpha = coupling.alpha();
            alpha.oldTime();
            exchangeStarted = true;
        }
        for (long k = 0; k < steps/couplingSteps; ++k)
        {
            // 1. The fluid crosses the coupling time with the exchange made at its start.
            for (label sub = 0; sub < interval->fluidSteps(); ++sub)
            {
                ++runTime;
                alpha = coupling.alpha();
                #include "UEqn.H"
                while (piso.correct())
                {
                    #include "pEqn.H"
                }
                p = p_rgh + gh;
                runTime.write();
            }

            // 2. The particles get the same momentum and the new pressure gradient.
            const volVectorField gradp("gradp", fvc::grad(p_rgh) + g);
            coupling.updateForces(particles, U, gradp);
            dem->setForces(particles, coupling.particleForces());

            // 3. LIGGGHTS crosses it; the next exchange starts from where both are.
            dem->advance(couplingSteps);
            particles = dem->gatherAll();
            coupling.updateFluidFraction(particles);
            coupling.updateExchange(particles, U);
        }
    };

    // The fluid's force on the ice, summed over the particles, as held over
    // the last coupling step: its vertical part, drag and pressure (buoyancy
    // and dynamic pressure).
    water.columns = {"fluidForceZ", "dragZ", "pressureForceZ"};
    water.values = [&]()
    {
        const vector drag = couplingPtr ? couplingPtr->totalDrag() : Zero;
        const vector pressure = couplingPtr ? couplingPtr->totalPressureForce() : Zero;
        return std::vector<double>{drag.z() + pressure.z(), drag.z(), pressure.z()};
    };

    Info<< "\nLoading the ridge of " << caseDir << " in water solved by OpenFOAM\n" << endl;
    demModelsAction([&]()
    {
        // The bond model's unused lanes compute 0/0 (FpeTrapsOff.H); the fluid
        // runs under the same guard, its fields' health shows in the forces.
        const ::iceCoupling::FpeTrapsOff untrapped;
        iceDEM::RidgeScene scene(MPI_COMM_WORLD, settings, &water);
        scene.run();
    });
    runTime.writeNow();

    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wallStart).count();
    Info<< "icePunchFoam: " << wall << " s wall clock" << nl << "End\n" << endl;
    return 0;
}
