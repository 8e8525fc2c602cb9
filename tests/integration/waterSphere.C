// Single spheres in hydrostatic water inside LIGGGHTS (WaterForces, one
// engine, no contacts between them):
//   - a 2 mm ice sphere released deep rises to its terminal velocity (then floats);
//   - a 15 mm nylon sphere (Ten Cate et al. 2002) sinks to its terminal velocity;
//   - a 10 mm ice sphere dropped onto the surface comes to rest at its draft.
// The velocity histories are checked against an accurate (RK4) solution of
// the submerged sphere's ODE with added mass, the end states against the
// algebraic terminal velocity (0.5 %) and the floating draft (1 %). Then the
// fix-order guards are exercised. Exit status 0 if every check passes.
//
// usage: mpirun -np N waterSphere

#include "HydrostaticWater.H"
#include "LiggghtsInstance.H"
#include "StlWriter.H"
#include "WaterForces.H"

#include "atom.h"
#include "lammps.h"

#include <mpi.h>

#include <cmath>
#include <functional>
#include <iomanip>
#include <iostream>
#include <sstream>

using namespace iceDEM;

namespace
{

struct Probe
{
    std::string name;
    double radius, density, x, z0;
    double worstHistoryError = 0.0;   // |v - v_ref| / |v_terminal| while submerged
    double vReference = 0.0;
    double vAt3s = 0.0;
};

int failures = 0;

void check(bool ok, const std::string& what)
{
    std::cout << (ok ? "  ok    " : "  FAIL  ") << what << std::endl;
    if (!ok) ++failures;
}

//- (m + C_a rho_w V) dv/dt = (rho_w - rho_p) V g - 0.5 rho_w C_d pi r^2 |v| v, written out.
double acceleration(const HydrostaticWaterParameters& w, double r, double rhoP, double v)
{
    const double volume = 4.0 / 3.0 * M_PI * r * r * r;
    double force = (w.density - rhoP) * volume * w.gravity;
    if (v != 0.0)
    {
        const double re = w.density * std::abs(v) * 2 * r / w.viscosity;
        const double cd = std::max(0.44, 24.0 / re * (1.0 + 0.15 * std::pow(re, 0.687)));
        force -= 0.5 * w.density * cd * M_PI * r * r * std::abs(v) * v;
    }
    return force / ((rhoP + w.addedMassCoefficient * w.density) * volume);
}

double rk4(const std::function<double(double)>& f, double y, double dt)
{
    const double k1 = f(y), k2 = f(y + 0.5 * dt * k1), k3 = f(y + 0.5 * dt * k2), k4 = f(y + dt * k3);
    return y + dt / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4);
}

} // namespace


int main(int argc, char** argv)
{
    MPI_Init(&argc, &argv);
    int rank = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);

    HydrostaticWaterParameters w;
    w.surfaceLevel = 0.0;
    const HydrostaticWater water(w);
    const double dt = 2e-4;

    std::vector<Probe> probes
    {
        {"ice sphere, r 1 mm, rising", 0.001, 917.0, -0.2, -0.5},
        {"nylon sphere, r 7.5 mm, sinking", 0.0075, 1120.0, 0.0, -0.2},
        {"ice sphere, r 5 mm, dropped on the surface", 0.005, 917.0, 0.2, 0.005}
    };

    {
        LiggghtsInstance lmp(MPI_COMM_WORLD, "log.waterSphere.liggghts");
        for (const char* c :
        {
            "atom_style sphere", "atom_modify map array", "boundary f f f", "newton off",
            "units si", "communicate single vel yes", "processors * 1 1",
            "region box block -0.4 0.4 -0.1 0.1 -12 0.2 units box", "create_box 1 box",
            "neighbor 0.05 bin", "neigh_modify delay 0",   // coarse bins: a tall, empty box
            "fix m1 all property/global kn peratomtypepair 1 1e3",
            "fix m2 all property/global kt peratomtypepair 1 1e3",
            "fix m3 all property/global gamman_abs peratomtypepair 1 0",
            "fix m4 all property/global gammat_abs peratomtypepair 1 0",
            "fix m5 all property/global coefficientFriction peratomtypepair 1 0.3",
            "fix m6 all property/global coefficientRollingFriction peratomtypepair 1 0.0",
            "pair_style gran model hooke/stiffness tangential history absolute_damping on",
            "pair_coeff * *", "timestep 2e-4",
            "fix gravity all gravity 9.81 vector 0 0 -1",
            // A floor nobody reaches: LIGGGHTS' wall fixes must not upset the order checks.
            "fix floor all wall/gran model hooke/stiffness tangential history "
            "primitive type 1 zplane -11.9 absolute_damping on"
        })
        {
            lmp.command(c);
        }
        // A moving mesh wall (a platen, as in the punch test) far from the
        // spheres: its fixes must not upset the order checks either.
        const std::string platen = "waterSphere.platen.stl";
        if (rank == 0)
        {
            writeCylinderStl(platen, Vec3(0.0, 0.0, -11.0), Vec3(1.0, 0.0, 0.0), 0.05, 0.1, 16, "platen");
        }
        MPI_Barrier(MPI_COMM_WORLD);
        lmp.command("fix platen all mesh/surface/stress file " + platen + " type 1");
        lmp.command("fix platenWall all wall/gran model hooke/stiffness tangential history mesh n_meshes 1 "
                    "meshes platen absolute_damping on");
        lmp.command("fix movePlaten all move/mesh mesh platen linear 0 0 -0.001");
        for (std::size_t k = 0; k < probes.size(); ++k)
        {
            const Probe& p = probes[k];
            std::ostringstream cmd;
            cmd << std::setprecision(17) << "create_atoms 1 single " << p.x << " 0 " << p.z0 << " units box";
            lmp.command(cmd.str());
            cmd.str("");
            cmd << std::setprecision(17) << "set atom " << k + 1 << " diameter " << 2 * p.radius
                << " density " << p.density;
            lmp.command(cmd.str());
        }

        WaterForces forces(lmp, water);
        forces.defineForceFix();
        forces.defineAddedMassFix();
        lmp.command("fix integrate all nve/sphere");
        lmp.command("run 0");

        LAMMPS_NS::Atom& atom = *lmp.engine().atom;
        auto state = [&](int tag, int component, double** a)
        {
            const int i = atom.map(tag);
            double v = (i >= 0 && i < atom.nlocal) ? a[i][component] : 0.0, sum = 0.0;
            MPI_Allreduce(&v, &sum, 1, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
            return sum;
        };

        const int chunk = 50;
        const double duration = 40.0;
        double kineticLastSecond = 0.0, draftErrorLastSecond = 0.0;
        const double floatingDraft = floatingSphereDraft(probes[2].radius, probes[2].density, w.density);
        for (int n = 0; n * chunk * dt < duration - 1e-9; ++n)
        {
            lmp.command("run " + std::to_string(chunk) + " pre no post no");
            const double t = (n + 1) * chunk * dt;
            for (int k = 0; k < 2; ++k)
            {
                Probe& p = probes[k];
                if (t > 3.0 + 1e-9) continue;   // both are at terminal velocity long before
                for (int s = 0; s < chunk * 10; ++s)
                {
                    p.vReference = rk4([&](double v) { return acceleration(w, p.radius, p.density, v); },
                                       p.vReference, dt / 10);
                }
                const double vt = terminalVelocity(water, p.radius, p.density);
                const double v = state(k + 1, 2, atom.v);
                p.worstHistoryError = std::max(p.worstHistoryError, std::abs(v - p.vReference) / std::abs(vt));
                p.vAt3s = v;
            }
            if (t > duration - 1.0)
            {
                const double z = state(3, 2, atom.x), v = state(3, 2, atom.v);
                const double mass = probes[2].density * 4.0 / 3.0 * M_PI * std::pow(probes[2].radius, 3);
                kineticLastSecond = std::max(kineticLastSecond, 0.5 * mass * v * v / (mass * w.gravity * probes[2].radius));
                draftErrorLastSecond = std::max(draftErrorLastSecond,
                    std::abs((w.surfaceLevel - (z - probes[2].radius)) / floatingDraft - 1.0));
            }
        }

        if (rank == 0) std::cout << "waterSphere: hydrostatic water in LIGGGHTS" << std::endl;
        for (int k = 0; k < 2; ++k)
        {
            const Probe& p = probes[k];
            const double vt = terminalVelocity(water, p.radius, p.density);
            const double v = p.vAt3s;
            if (rank == 0)
            {
                std::ostringstream s;
                s << p.name << ": v(3 s) " << v << " m/s, terminal " << vt << " m/s (error "
                  << (v / vt - 1.0) * 100 << " %), worst history error " << p.worstHistoryError * 100
                  << " % of v_terminal";
                check(std::abs(v / vt - 1.0) < 5e-3 && p.worstHistoryError < 5e-3, s.str());
            }
        }
        if (rank == 0)
        {
            std::ostringstream s;
            s << probes[2].name << ": draft within " << draftErrorLastSecond * 100
              << " % of " << floatingDraft << " m, kinetic energy <= " << kineticLastSecond
              << " m g r in the last second";
            check(draftErrorLastSecond < 0.01 && kineticLastSecond < 1e-6, s.str());
        }

        const WaterForceTotals totals = forces.totals();
        if (rank == 0)
        {
            // The nylon sphere is submerged; both ice spheres float by now.
            auto volume = [](double r) { return 4.0 / 3.0 * M_PI * r * r * r; };
            const double expected = volume(probes[1].radius)
                + 917.0 / w.density * (volume(probes[0].radius) + volume(probes[2].radius));
            std::ostringstream s;
            s << "summed submerged volume " << totals.submergedVolume << " m3 against " << expected;
            check(std::abs(totals.submergedVolume / expected - 1.0) < 1e-3
                  && std::abs(totals.buoyancy.z() - w.density * w.gravity * totals.submergedVolume) < 1e-12, s.str());
        }

        if (rank == 0)
        {
            check(forces.failure().empty(), "no order problem reported with gravity, wall and moving-mesh fixes"
                  + (forces.failure().empty() ? std::string() : ": " + forces.failure()));
        }
        // Guards: a force fix after the added-mass fix is reported ...
        lmp.command("fix late all external pf/callback 1 1");
        lmp.command("run 1 pre no post no");
        if (rank == 0) check(!forces.failure().empty(), "a force fix after waterAddedMass is reported: " + forces.failure());
        // ... and the water force fix after another external fix is refused.
        WaterForces second(lmp, water);
        bool refused = false;
        try { second.defineForceFix(); } catch (const std::logic_error& e) { refused = true; }
        if (rank == 0) check(refused, "waterForces defined after another fix external is refused");
    }
    MPI_Finalize();
    return failures == 0 ? 0 : 1;
}
