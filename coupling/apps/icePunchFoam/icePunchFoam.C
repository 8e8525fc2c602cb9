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
    #include "checkFluidMesh.H"
    #include "createMesh.H"

    ::iceCoupling::MpiForSerialRun mpi;
    pisoControl piso(mesh);

    const word hydrostaticApplication("ridgeDEM");
    #include "createFields.H"

    #include "couplingSteps.H"
    #include "readRidgeSettings.H"

    const word surfaceSource("DEM/ridge.h5; postProcessing/geometry.json waterLevel");
    #include "punchCouplingTime.H"
    #include "sceneWater.H"
    #include "loadRidge.H"
    return 0;
}
