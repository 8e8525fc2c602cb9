// Inertia scaling inside LIGGGHTS (InertiaScalingFix; issue 17), GoogleTest
// under mpirun -np 1:
//   - after every force law has run, each sphere's total force AND torque are
//     divided by the factor (two spheres in a sheared contact, which gives
//     forces and torques, and a third in water with buoyancy, drag and added
//     mass), in either order with the water's added-mass fix;
//   - a sphere sinking in water follows (s (m + m_a)) dv/dt = F(v);
//   - a force fix defined after it is reported; a factor of 1 defines nothing.
#include "HydrostaticWater.H"
#include "InertiaScalingFix.H"
#include "LiggghtsInstance.H"
#include "WaterForces.H"

#include "atom.h"
#include "lammps.h"
#include "modify.h"

#include <gtest/gtest.h>
#include <mpi.h>

#include <array>
#include <cmath>
#include <functional>
#include <iomanip>
#include <memory>
#include <sstream>
#include <vector>

using namespace iceDEM;

namespace
{

enum class Order { inertiaLast, addedMassLast };

struct Engine
{
    std::unique_ptr<LiggghtsInstance> lmp;
    std::unique_ptr<WaterForces> water;
    std::unique_ptr<InertiaScalingFix> inertia;
};

HydrostaticWaterParameters stillWater()
{
    HydrostaticWaterParameters w;
    w.surfaceLevel = 0.0;
    return w;
}

void createSphere(LiggghtsInstance& lmp, int tag, const std::array<double, 3>& x, double radius, double density)
{
    std::ostringstream cmd;
    cmd << std::setprecision(17) << "create_atoms 1 single " << x[0] << " " << x[1] << " " << x[2] << " units box";
    lmp.command(cmd.str());
    cmd.str("");
    cmd << std::setprecision(17) << "set atom " << tag << " diameter " << 2 * radius << " density " << density;
    lmp.command(cmd.str());
}

//- Three spheres in water under gravity: 1 and 2 overlap and slide past each
//  other (contact force and torque), 3 sinks alone. Runs `steps` steps with
//  buoyancy and drag only (the contact's tangential history builds up), then
//  defines the added mass and the inertia scaling (factor) in `order` and
//  computes the forces again (run 0).
Engine makeEngine(double factor, Order order, int steps = 5)
{
    Engine e;
    e.lmp = std::make_unique<LiggghtsInstance>(MPI_COMM_WORLD, "log.inertiaScalingFix.liggghts");
    LiggghtsInstance& lmp = *e.lmp;
    for (const char* c :
    {
        "atom_style sphere", "atom_modify map array", "boundary f f f", "newton off",
        "units si", "communicate single vel yes", "processors * 1 1",
        "region box block -0.5 0.5 -0.5 0.5 -2 0.2 units box", "create_box 1 box",
        "neighbor 0.005 bin", "neigh_modify delay 0",
        "fix m1 all property/global kn peratomtypepair 1 1e5",
        "fix m2 all property/global kt peratomtypepair 1 4e4",
        "fix m3 all property/global gamman_abs peratomtypepair 1 0.5",
        "fix m4 all property/global gammat_abs peratomtypepair 1 0.2",
        "fix m5 all property/global coefficientFriction peratomtypepair 1 0.3",
        "fix m6 all property/global coefficientRollingFriction peratomtypepair 1 0.05",
        "pair_style gran model hooke/stiffness tangential history rolling_friction epsd2 absolute_damping on",
        "pair_coeff * *", "timestep 1e-5",
        "fix gravity all gravity 9.81 vector 0 0 -1"
    })
    {
        lmp.command(c);
    }
    createSphere(lmp, 1, {0.0, 0.0, -0.5}, 0.01, 917.0);
    createSphere(lmp, 2, {0.0195, 0.0, -0.5}, 0.01, 917.0);
    createSphere(lmp, 3, {0.3, 0.0, -0.5}, 0.0075, 1120.0);
    lmp.command("velocity all set 0 0 0");
    lmp.command("group pair id 2");
    lmp.command("velocity pair set 0 0.2 0.05");
    lmp.command("fix integrate all nve/sphere");

    e.water = std::make_unique<WaterForces>(lmp, HydrostaticWater(stillWater()));
    e.water->defineForceFix();
    e.inertia = std::make_unique<InertiaScalingFix>(lmp, factor);
    lmp.command("run " + std::to_string(steps));
    // Now the two scalings, in either order.
    if (order == Order::inertiaLast)
    {
        e.water->defineAddedMassFix();
        e.inertia->define();
    }
    else
    {
        e.inertia->define();
        e.water->defineAddedMassFix();
    }
    lmp.command("run 0");
    return e;
}

struct Loads
{
    std::vector<std::array<double, 3>> force, torque;
};

Loads loadsOf(const Engine& e)
{
    LAMMPS_NS::Atom& atom = *e.lmp->engine().atom;
    Loads l;
    for (int tag = 1; tag <= 3; ++tag)
    {
        const int i = atom.map(tag);
        l.force.push_back({atom.f[i][0], atom.f[i][1], atom.f[i][2]});
        l.torque.push_back({atom.torque[i][0], atom.torque[i][1], atom.torque[i][2]});
    }
    return l;
}

} // namespace


TEST(InertiaScalingFix, factorOneDefinesNothing)
{
    Engine e = makeEngine(1.0, Order::inertiaLast);
    EXPECT_FALSE(e.inertia->defined());
    EXPECT_LT(e.lmp->engine().modify->find_fix(InertiaScalingFix::fixId), 0);
}


TEST(InertiaScalingFix, dividesTotalForceAndTorqueByTheFactor)
{
    // Both orders, against the unscaled engine (the same added mass), component by component.
    const Loads one = loadsOf(makeEngine(1.0, Order::inertiaLast));
    // The scene gives what it promises: forces and torques on the sliding pair.
    for (int k = 0; k < 2; ++k)
    {
        EXPECT_GT(std::hypot(one.torque[k][0], one.torque[k][2]), 0.0) << "no torque on sphere " << k + 1;
        EXPECT_GT(std::abs(one.force[k][1]), 0.0) << "no tangential force on sphere " << k + 1;
    }
    for (double s : {10.0, 100.0})
    {
        for (Order order : {Order::inertiaLast, Order::addedMassLast})
        {
            Engine e = makeEngine(s, order);
            EXPECT_TRUE(e.inertia->defined());
            EXPECT_TRUE(e.inertia->failure().empty()) << e.inertia->failure();
            EXPECT_TRUE(e.water->failure().empty()) << e.water->failure();
            const Loads scaled = loadsOf(e);
            for (int a = 0; a < 3; ++a)
            {
                for (int k = 0; k < 3; ++k)
                {
                    const double tolerance = 1e-14 * (std::abs(one.force[a][k]) / s) + 1e-300;
                    EXPECT_NEAR(scaled.force[a][k], one.force[a][k] / s, tolerance)
                        << "force, sphere " << a + 1 << ", component " << k << ", s " << s;
                    EXPECT_NEAR(scaled.torque[a][k], one.torque[a][k] / s, 1e-14 * std::abs(one.torque[a][k]) / s + 1e-300)
                        << "torque, sphere " << a + 1 << ", component " << k << ", s " << s;
                }
            }
        }
    }
}


TEST(InertiaScalingFix, sinkingSphereFollowsTheScaledInertiaWithAddedMass)
{
    // The nylon sphere (tag 3): (s (m + C_a rho_w V)) dv/dt = (rho_w - rho_p) V g - drag(v).
    const double s = 10.0, r = 0.0075, rhoP = 1120.0, dt = 1e-5;
    const HydrostaticWaterParameters w = stillWater();
    const HydrostaticWater water(w);
    auto acceleration = [&](double v)
    {
        const double volume = 4.0 / 3.0 * M_PI * r * r * r;
        double force = (w.density - rhoP) * volume * w.gravity;
        if (v != 0.0)
        {
            const double re = w.density * std::abs(v) * 2 * r / w.viscosity;
            const double cd = std::max(0.44, 24.0 / re * (1.0 + 0.15 * std::pow(re, 0.687)));
            force -= 0.5 * w.density * cd * M_PI * r * r * std::abs(v) * v;
        }
        return force / (s * (rhoP + w.addedMassCoefficient * w.density) * volume);
    };
    Engine e = makeEngine(s, Order::inertiaLast, 0);
    LAMMPS_NS::Atom& atom = *e.lmp->engine().atom;
    const double vt = terminalVelocity(water, r, rhoP);
    double reference = 0.0, worst = 0.0, v = 0.0;
    const int chunk = 2000;
    for (int n = 0; n < 30; ++n)    // 0.6 s: a third of the way to the terminal velocity at s = 10
    {
        e.lmp->command("run " + std::to_string(chunk) + " pre no post no");
        for (int k = 0; k < chunk; ++k)
        {
            const double k1 = acceleration(reference), k2 = acceleration(reference + 0.5 * dt * k1);
            const double k3 = acceleration(reference + 0.5 * dt * k2), k4 = acceleration(reference + dt * k3);
            reference += dt / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4);
        }
        v = atom.v[atom.map(3)][2];
        worst = std::max(worst, std::abs(v - reference) / std::abs(vt));
    }
    EXPECT_LT(worst, 2e-3) << "v " << v << " m/s against " << reference << " (terminal " << vt << ")";
    // Not the unscaled motion, which would be near its terminal velocity by now.
    EXPECT_LT(std::abs(v), 0.5 * std::abs(vt));
    EXPECT_GT(std::abs(v), 0.1 * std::abs(vt));
}


TEST(InertiaScalingFix, forceFixDefinedAfterItIsReported)
{
    Engine e = makeEngine(10.0, Order::inertiaLast);
    EXPECT_TRUE(e.inertia->orderProblem().empty());
    e.lmp->command("fix late all external pf/callback 1 1");
    EXPECT_FALSE(e.inertia->orderProblem().empty());
    e.lmp->command("run 1 pre no post no");
    EXPECT_NE(e.inertia->failure().find("late"), std::string::npos) << e.inertia->failure();
}


int main(int argc, char** argv)
{
    MPI_Init(&argc, &argv);
    ::testing::InitGoogleTest(&argc, argv);
    const int result = RUN_ALL_TESTS();
    MPI_Finalize();
    return result;
}
