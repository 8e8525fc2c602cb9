/*---------------------------------------------------------------------------*\
Application
    icePunchInterFoam

Description
    The loading stage of the ridge scenes (rubble punch, ridge flexure) at
    the vof level: water and air with a moving free surface (iceInterFoam's
    volume of fluid), so that the ice pushed under raises the water level of
    the closed box, as in the experiment, whose buoyancy share was read from
    that rise. The assembled ridge (DEM/ridge.h5, from ridgeDEM -stage
    assemble) is loaded by demModels' RidgeScene and PlatenLoading, as
    icePunchFoam loads it at the cfd level; the water starts flat where the
    ridge floats (postProcessing/geometry.json waterLevel), with air above it
    to the mesh's top.

    The particles get the vof level's forces (coupling/README.md "vof
    level"): drag from the local mixture, the buoyancy of their caps under
    their columns' water height, the dynamic pressure gradient. The platen is
    a DEM mesh wall only: it displaces no water, so the level rises with the
    ice alone (its own share is the force curve's platenBuoyancy).

    One coupling step: the fluid crosses the coupling time with the exchange
    made at its start (momentum, pressure, then alpha.water); the particles
    get the same momentum and the new pressure; LIGGGHTS crosses it; the
    particles are located and the exchange updated.

    Input: constant/couplingProperties (waterLevel vof; hydrostatic { } for
    the assembly; vof { }: the coupling's models, couplingInterval in DEM
    steps, optional waveDamping), constant/transportProperties (phases
    (water air)), constant/g, 0/U, 0/p_rgh, 0/alpha.water, system/controlDict
    (OpenFOAM's: deltaT the largest fluid step; maxCo, maxAlphaCo),
    system/loadingDict (the loading control), constant/ridgeProperties,
    constant/iceProperties, constant/freezeBondProperties, DEM/in.ridge,
    DEM/ridge.h5.
    Output: as ridgeDEM's loading stage (postProcessing/platenForce.csv with
    the water's columns: its force on the ice, the water level, the ice's
    submerged volume under the moving surface), postProcessing/vof.csv, the
    fluid fields in the time directories.
\*---------------------------------------------------------------------------*/

#include "fvCFD.H"
#include "pisoControl.H"
#include "OFstream.H"
#include "CMULES.H"
#include "immiscibleIncompressibleTwoPhaseMixture.H"
#include "particleFluidCoupling.H"
#include "freeSurface.H"
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

namespace
{

#include "vofChecks.H"

} // namespace


int main(int argc, char *argv[])
{
    argList::addNote
    (
        "Loading stage of the ridge scenes with water and air and a moving surface (vof level)"
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

    const freeSurface surface(mesh);
    const courantLimits limits(runTime.controlDict(), levelProperties);
    const volScalarField waveDamping(waveDampingRate(mesh, vofProperties));

    #include "punchCouplingTime.H"
    #include "sceneWaterVof.H"
    #include "loadRidge.H"
    return 0;
}
