/*---------------------------------------------------------------------------*\
Application
    iceRubbleFoam

Description
    The settling stage of a rubble beam (cases/rubbleBeam, ./Allrun -water
    cfd) at the cfd level: demModels' RubbleScene rains the blocks into the
    box and lets them settle, as rubbleDEM -stage settle does in hydrostatic
    water, while OpenFOAM solves the water as iceFoam does (unresolved
    CFD-DEM, "model A", PISO on p_rgh, laminar; coupling/README.md): drag,
    -V grad(p) (buoyancy and dynamic pressure) and the fluid fraction come
    from the coupling.

    The fluid mesh is the box below the still surface (hydrostatic.surfaceLevel
    of constant/couplingProperties), open at the top: blocks rained from above
    get the fluid's forces on their submerged caps only. The surface does not
    move (no VOF). The settled rubble (DEM/settled.h5) is saved as rubbleDEM
    saves it, with what made it (the water's files included), so that
    rubbleDEM -stage compact and -stage bond, the punch and the ridges start
    from it as from a hydrostatic one; postProcessing/settling.json gives the
    layer, the water's force on it and the cost.

    A killed settling starts again: it has no checkpoint of the fluid.

    Input: constant/couplingProperties (waterLevel cfd; hydrostatic { } for
    the surface and the later stages; cfd { }: the coupling's models,
    couplingInterval in DEM steps), constant/transportProperties, constant/g,
    0/U, 0/p_rgh, system/controlDict (OpenFOAM's: deltaT is the largest fluid
    step), constant/rubbleProperties, constant/iceProperties,
    constant/freezeBondProperties, DEM/in.rubbleBeam.
    Output: DEM/settled.h5, postProcessing/settling.json, the fluid fields in
    the time directories.
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
#include "RubbleScene.H"

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
        "Settling stage of a rubble beam with the water solved by OpenFOAM (cfd level)"
    );
    argList::noFunctionObjects();
    argList::addOption("shape", "cuboid|empirical", "block shape instead of blocks.shape");
    #include "setRootCaseLists.H"
    #include "createTime.H"
    #include "checkFluidMesh.H"
    #include "createMesh.H"

    ::iceCoupling::MpiForSerialRun mpi;
    pisoControl piso(mesh);

    const word hydrostaticApplication("rubbleDEM");
    #include "createFields.H"
    #include "couplingSteps.H"
    const fileName caseDir(runTime.globalPath());

    iceDEM::RubbleSettings settings;
    demModelsAction([&]()
    {
        settings = iceDEM::RubbleSettings::readCase(caseDir, "settle", args.getOrDefault<word>("shape", ""));
    });

    const auto wallStart = std::chrono::steady_clock::now();
    const word surfaceSource("constant/couplingProperties hydrostatic.surfaceLevel");
    const auto checkCouplingTime = [](double) {};
    #include "sceneWater.H"

    Info<< "\nSettling the rubble of " << caseDir << " in water solved by OpenFOAM\n" << endl;
    demModelsAction([&]()
    {
        // The bond model's unused lanes compute 0/0 (FpeTrapsOff.H); the fluid
        // runs under the same guard, its fields' health shows in the forces.
        const ::iceCoupling::FpeTrapsOff untrapped;
        iceDEM::RubbleScene scene(MPI_COMM_WORLD, settings, &water);
        scene.run();
    });
    runTime.writeNow();

    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wallStart).count();
    Info<< "iceRubbleFoam: " << wall << " s wall clock" << nl << "End\n" << endl;
    return 0;
}
