/*---------------------------------------------------------------------------*\
Application
    iceInterFoam

Description
    The vof level: water and air (interFoam's volume of fluid, OpenFOAM's
    immiscibleIncompressibleTwoPhaseMixture) with a moving free surface,
    coupled both ways to the ice particles in LIGGGHTS as iceFoam couples
    them (the same drag, fluid-fraction and momentum-coupling models, the
    same DEM start-up, createDem.H).

    The particles' fluid fraction eps enters both phases' continuity:
        ddt(eps) + div(phi) = 0,  ddt(eps alpha) + div(alphaPhi) = 0
    with phi the superficial flux of the mixture; each fluid step solves the
    momentum and the pressure first, then alpha.water with the flux that
    satisfies the first equation, so that water is neither made nor lost
    where particles come and go (alpha 1 stays 1).
    The particles get the drag from the local mixture (rho, nu at their
    samples) and the buoyancy rho_w g V_cap of the spherical cap under the
    water height of their columns (read from alpha.water), plus the dynamic
    pressure gradient (the part of grad p that is not hydrostatic) on the
    same volume: at rest exactly Archimedes, whatever the interface's smear.

    Input: constant/couplingProperties (hydrodynamics vof; a vof
    sub-dictionary: initialLevel, optional waveDamping {width; rate;}),
    constant/transportProperties (phases (water air), sigma),
    constant/g (along -z), 0/U, 0/p_rgh, 0/alpha.water; system/controlDict
    maxCo, maxAlphaCo (<= 0.5: the measured limits, coupling/README.md).
    Output: as iceFoam, and postProcessing/vof.csv (water volume, the level
    of the particle-free columns, Courant numbers, buoyancy per coupling step).
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
#include "BondedIce.H"
#include "MpiForSerialRun.H"
#include "demModelsAction.H"

#include <mpi.h>

#include <chrono>
#include <memory>

using namespace Foam::iceCoupling;
using ::iceCoupling::demModelsAction;

namespace
{

#include "particleOutput.H"
#include "bondedIceOutput.H"
#include "vofChecks.H"

} // namespace


int main(int argc, char *argv[])
{
    argList::addNote
    (
        "Water and air with a moving surface (OpenFOAM VOF) coupled both ways with"
        " the ice particles (LIGGGHTS)"
    );
    #include "postProcess.H"
    #include "setRootCaseLists.H"
    #include "createTime.H"
    #include "createMesh.H"

    ::iceCoupling::MpiForSerialRun mpi;
    pisoControl piso(mesh);

    #include "createFields.H"

    const freeSurface surface(mesh);
    const courantLimits limits(runTime.controlDict(), couplingProperties);
    {
        const scalar level = vofProperties.get<scalar>("initialLevel");
        if (level <= surface.bottom() || level >= surface.top())
        {
            FatalIOErrorInFunction(couplingProperties)
                << "entry 'vof/initialLevel' is " << level << " m: the water surface must lie"
                << " inside the mesh, between its bottom z = " << surface.bottom() << " and top z = "
                << surface.top() << " m (system/blockMeshDict), with air above it" << exit(FatalIOError);
        }
        if (runTime.timeName() == "0")   // a run from a later time keeps its alpha.water
        {
            const scalar stillLevel = level;
            #include "setStillWater.H"
        }
    }
    const volScalarField waveDamping(waveDampingRate(mesh, vofProperties));

    const auto wallStart = std::chrono::steady_clock::now();

    #include "createDem.H"

    if (runTime.controlDict().getOrDefault("adjustTimeStep", false))
    {
        FatalIOErrorInFunction(runTime.controlDict())
            << "entry 'adjustTimeStep': must be off; the fluid advances each coupling"
            << " time in a fixed whole number of steps" << exit(FatalIOError);
    }
    const couplingInterval interval(couplingProperties, lmp.timeStep(), runTime.deltaTValue());
    Info<< "Coupling every " << interval.demSteps() << " DEM steps (" << interval.time()
        << " s): " << interval.fluidSteps() << " fluid step(s) per coupling step" << nl << endl;

    std::vector<::iceCoupling::CouplingParticle> particles(dem.gatherAll());
    checkCellsHoldParticles(mesh, surface, couplingProperties, particles);
    checkHeaveCoupling(couplingProperties, particles, interval, rho1.value(), mag(g.value()));
    particleFluidCoupling coupling
    (
        mesh, couplingProperties, rho1.value(), gAverage(mixture.nuModel1().nu()().primitiveField()),
        interval.time()
    );
    // mixture.nu() refers to the mixture's own field, which mixture.correct() updates.
    coupling.setMixture(rho, mixture.nu()(), rho1.value(), mag(g.value()));
    particleOutput output(runTime, couplingProperties);
    vofOutput vofLog(runTime, surface);

    particles = dem.gatherNear(coupling.particleRegion());
    coupling.updateFluidFraction(particles);
    coupling.updateExchange(particles, U);
    eps = coupling.alpha();
    eps.oldTime();
    epsRho = eps*rho;
    epsRho.oldTime();
    const scalar waterVolume0 = surface.waterVolume(alpha1, eps);
    Info<< "Water volume " << waterVolume0 << " m^3, level " << surface.freeLevel(alpha1, eps) << " m" << nl << endl;

    Info<< "\nStarting time loop\n" << endl;
    while (runTime.run())
    {
        // 1. The fluid crosses the coupling time with the exchange made at its start.
        courantNumbers courant;
        for (label sub = 0; sub < interval.fluidSteps(); ++sub)
        {
            #include "vofFluidStep.H"
            runTime.printExecutionTime(Info);
        }

        // 2. The particles get the same momentum over the same time: drag,
        //    the buoyancy of their caps under the water height and the
        //    dynamic pressure gradient (zero at rest).
        const volVectorField gradpd
        (
            "gradpd",
            fvc::reconstruct((fvc::snGrad(p_rgh) + ghf*fvc::snGrad(rho))*mesh.magSf())
        );
        const scalarField height(surface.columnHeight(alpha1));
        coupling.setWaterHeight(height);
        coupling.updateForces(particles, U, gradpd);
        dem.setForces(particles, coupling.particleForces());
        output.coupling(lmp.time(), coupling, dem);
        vofLog.write(lmp.time(), alpha1, eps, waterVolume0, courant, coupling);
        checkWaterVolume(couplingProperties, surface.waterVolume(alpha1, eps), waterVolume0, runTime);

        // 3. LIGGGHTS crosses it; the next exchange starts from where both are.
        dem.advance(interval.demSteps());
        particles = dem.gatherNear(coupling.particleRegion());
        coupling.updateFluidFraction(particles);
        coupling.updateExchange(particles, U);
        bondedIceAfterAdvance(bondedIce.get(), lmp.time(), runTime.writeTime(), bondHistory);
        if (runTime.writeTime())
        {
            output.particlesVtk(runTime, dem);
        }
    }
    bondedIceAtEnd(bondedIce.get(), bondHistory);

    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wallStart).count();
    Info<< "Water volume " << surface.waterVolume(alpha1, eps) << " m^3 ("
        << surface.waterVolume(alpha1, eps)/waterVolume0 - 1 << " relative to the start)" << nl
        << "Coupled run: " << wall << " s wall clock" << nl << "End\n" << endl;
    return 0;
}
