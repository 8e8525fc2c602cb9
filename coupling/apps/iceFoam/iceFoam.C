/*---------------------------------------------------------------------------*\
Application
    iceFoam

Description
    Unresolved CFD-DEM: transient incompressible water (PISO on p_rgh, laminar)
    with fluid fraction and gravity, coupled both ways to the ice particles in
    LIGGGHTS, which runs as a library in this process on every rank.

    Volume-averaged equations ("model A": the particles get -V_p grad(p) and
    the drag, the fluid the reaction of both), kinematic pressure
    p = p_rgh + g.x:
        ddt(alpha) + div(alpha U) = 0
        ddt(alpha U) + div(alpha U U) - div(alpha nu grad U)
            = -alpha grad(p_rgh) + Ksl (Us - U)

    Per coupling step, from a state where both codes are at time t, the
    particles located and the drag coefficients K computed from their slip:
      1. the fluid advances to t + T_c (a whole number of its steps) with
         its share of the drag, -Ksl (U - Us) implicit in U (semiImplicit) or
         frozen at t (explicit);
      2. the particle forces for the same interval are computed with the same
         K and the fluid velocity the fluid solved with (the new one for
         semiImplicit, the frozen one for explicit) and the new grad(p):
         each particle gets exactly the momentum the fluid gave up;
      3. LIGGGHTS advances couplingInterval steps with them; the particles are
         located, alpha, Us and K updated.
    docs/architecture.md lists DEM first, then the exchange, then the fluid;
    that order gives the fluid the exchange one interval before the particles
    get it and, semi-implicit, lets fluid and particles see different fluid
    velocities, which lost up to 40 % of the momentum in a test (cases in
    tests/coupling/lightCloud); this order is conservative to round-off.
    Stability limits: momentumCouplingModel::slipGrowthFactor.

    Input: constant/couplingProperties, constant/transportProperties (rho, nu),
    constant/g, 0/U, 0/p_rgh, the DEM script it names; with
    constant/iceProperties the particles are bonded ice (BondedIce: bonds,
    contacts and hysteretic damping from demModels).
    Output: the usual time directories (U, p_rgh, p, alpha, Us),
    postProcessing/coupling.csv (forces and fluid-fraction range per coupling
    step), postProcessing/particles.csv (trajectories), particle VTK files
    at write times (postProcessing/particles/) and, for bonded ice,
    postProcessing/bonds.csv (intact and broken bonds per coupling step).
\*---------------------------------------------------------------------------*/

#include "fvCFD.H"
#include "pisoControl.H"
#include "OFstream.H"
#include "particleFluidCoupling.H"
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

} // namespace


int main(int argc, char *argv[])
{
    argList::addNote
    (
        "Water (OpenFOAM) coupled both ways with the ice particles (LIGGGHTS)"
    );
    #include "postProcess.H"
    #include "setRootCaseLists.H"
    #include "createTime.H"
    #include "createMesh.H"

    ::iceCoupling::MpiForSerialRun mpi;
    pisoControl piso(mesh);

    #include "createFields.H"

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

    particleFluidCoupling coupling(mesh, couplingProperties, rho.value(), nu.value(), interval.time());
    particleOutput output(runTime, couplingProperties);

    // The exchange's own cost (particles to the fluid ranks, locating, sums
    // over the ranks, forces back), reported at the end.
    double exchangeSeconds = 0;
    const auto timed = [&exchangeSeconds](auto&& action)
    {
        const auto start = std::chrono::steady_clock::now();
        action();
        exchangeSeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    };
    std::vector<::iceCoupling::CouplingParticle> particles;
    timed([&]()
    {
        particles = dem.gatherNear(coupling.particleRegion());
        coupling.updateFluidFraction(particles);
        coupling.updateExchange(particles, U);
    });
    alpha = coupling.alpha();
    alpha.oldTime();

    Info<< "\nStarting time loop\n" << endl;
    while (runTime.run())
    {
        // 1. The fluid crosses the coupling time with the exchange made at its start.
        for (label sub = 0; sub < interval.fluidSteps(); ++sub)
        {
            ++runTime;
            Info<< "Time = " << runTime.timeName() << nl << endl;
            // The fluid fraction of the particles' latest positions; ddt(alpha)
            // feeds continuity at the first fluid step of the coupling step.
            alpha = coupling.alpha();
            #include "CourantNo.H"
            #include "UEqn.H"
            while (piso.correct())
            {
                #include "pEqn.H"
            }
            p = p_rgh + gh;
            runTime.write();
            runTime.printExecutionTime(Info);
        }

        // 2. The particles get the same momentum over the same time, and the
        //    fluid's new pressure gradient.
        const volVectorField gradp("gradp", fvc::grad(p_rgh) + g);
        timed([&]()
        {
            coupling.updateForces(particles, U, gradp);
            dem.setForces(particles, coupling.particleForces());
        });
        output.coupling(lmp.time(), coupling, dem);

        // 3. LIGGGHTS crosses it; the next exchange starts from where both are.
        dem.advance(interval.demSteps());
        timed([&]()
        {
            particles = dem.gatherNear(coupling.particleRegion());
            coupling.updateFluidFraction(particles);
            coupling.updateExchange(particles, U);
        });
        bondedIceAfterAdvance(bondedIce.get(), lmp.time(), runTime.writeTime(), bondHistory);
        if (runTime.writeTime())
        {
            output.particlesVtk(runTime, dem);
        }
    }
    bondedIceAtEnd(bondedIce.get(), bondHistory);

    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wallStart).count();
    const label held = particles.size();
    // Its collectives also wait for the rank whose DEM or fluid step took longest.
    Info<< "Coupling exchange: " << returnReduce(exchangeSeconds, minOp<scalar>()) << " to "
        << returnReduce(exchangeSeconds, maxOp<scalar>()) << " s of the wall clock on a rank"
        << " (waits for the other ranks included); particles near each rank's part of the mesh at the end: "
        << returnReduce(held, minOp<label>()) << " to " << returnReduce(held, maxOp<label>()) << " of "
        << dem.particleCount() << nl;
    Info<< "Coupled run: " << wall << " s wall clock" << nl << "End\n" << endl;
    return 0;
}
