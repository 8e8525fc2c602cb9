#include "HydrostaticWater.H"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>

using namespace iceDEM;

namespace
{

constexpr double waterDensity = 1000.0;
constexpr double waterViscosity = 1.79e-3;
constexpr double g = 9.81;

HydrostaticWaterParameters water(double surfaceLevel = 0.0)
{
    HydrostaticWaterParameters p;
    p.surfaceLevel = surfaceLevel;
    p.density = waterDensity;
    p.viscosity = waterViscosity;
    p.gravity = g;
    p.addedMassCoefficient = 0.5;
    return p;
}

double sphereVolume(double r)
{
    return 4.0 / 3.0 * M_PI * r * r * r;
}

//- Volume of the part of a sphere below z = depth - r (centre at 0) by the
//  midpoint rule on thin discs: independent of the cap formula.
double integratedCapVolume(double r, double depth, int slices = 200000)
{
    const double top = std::min(depth - r, r);
    if (top <= -r) return 0.0;
    const double dz = (top + r) / slices;
    double v = 0.0;
    for (int k = 0; k < slices; ++k)
    {
        const double z = -r + (k + 0.5) * dz;
        v += M_PI * (r * r - z * z) * dz;
    }
    return v;
}

} // namespace


TEST(SubmergedSphereVolume, LimitsAboveBelowAndHalf)
{
    const double r = 0.0275;
    EXPECT_EQ(submergedSphereVolume(r, -0.01), 0.0);
    EXPECT_EQ(submergedSphereVolume(r, 0.0), 0.0);
    EXPECT_DOUBLE_EQ(submergedSphereVolume(r, 2.0 * r), sphereVolume(r));
    EXPECT_DOUBLE_EQ(submergedSphereVolume(r, 5.0 * r), sphereVolume(r));
    EXPECT_DOUBLE_EQ(submergedSphereVolume(r, r), 0.5 * sphereVolume(r));
}


TEST(SubmergedSphereVolume, CapFormulaAndNumericIntegration)
{
    const double r = 0.05;
    for (double h : {0.001, 0.013, 0.04, 0.05, 0.071, 0.0999})
    {
        const double formula = M_PI * h * h * (r - h / 3.0);   // pi h^2 (3r - h) / 3
        EXPECT_NEAR(submergedSphereVolume(r, h), formula, 1e-15) << "h " << h;
        EXPECT_NEAR(submergedSphereVolume(r, h) / integratedCapVolume(r, h), 1.0, 1e-8) << "h " << h;
        // The part above plus the part below is the whole sphere.
        EXPECT_NEAR(submergedSphereVolume(r, h) + submergedSphereVolume(r, 2 * r - h), sphereVolume(r), 1e-15);
    }
}


TEST(HydrostaticWater, SubmergedSphereBuoyancyIsArchimedes)
{
    const HydrostaticWater w(water(1.5));
    const double r = 0.0275;
    const SphereWaterLoad load = w.sphereLoad(r, 1.5 - r - 1e-9, Vec3::Zero());
    EXPECT_DOUBLE_EQ(load.submergedVolume, sphereVolume(r));
    EXPECT_DOUBLE_EQ(load.buoyancy.z(), waterDensity * g * sphereVolume(r));
    EXPECT_EQ(load.buoyancy.x(), 0.0);
    EXPECT_EQ(load.buoyancy.y(), 0.0);
    EXPECT_EQ(load.drag, Vec3::Zero());
    EXPECT_DOUBLE_EQ(load.addedMass, 0.5 * waterDensity * sphereVolume(r));

    const SphereWaterLoad dry = w.sphereLoad(r, 1.5 + r, Vec3(0.3, 0.0, -1.0));
    EXPECT_EQ(dry.submergedVolume, 0.0);
    EXPECT_EQ(dry.buoyancy, Vec3::Zero());
    EXPECT_EQ(dry.drag, Vec3::Zero());
    EXPECT_EQ(dry.addedMass, 0.0);

    // Centre at the surface: half of everything.
    const SphereWaterLoad half = w.sphereLoad(r, 1.5, Vec3::Zero());
    EXPECT_NEAR(half.buoyancy.z() / (0.5 * waterDensity * g * sphereVolume(r)), 1.0, 1e-14);
}


TEST(SchillerNaumann, ValuesAtSeveralReynoldsNumbers)
{
    // 24/Re (1 + 0.15 Re^0.687) worked out by hand.
    EXPECT_NEAR(schillerNaumannDragCoefficient(0.01), 2400.0 * (1.0 + 0.15 * 0.0422669), 1e-3);
    EXPECT_NEAR(schillerNaumannDragCoefficient(1.0), 27.6, 1e-12);
    EXPECT_NEAR(schillerNaumannDragCoefficient(10.0), 2.4 * (1.0 + 0.15 * 4.864072), 1e-5);
    EXPECT_NEAR(schillerNaumannDragCoefficient(100.0), 0.24 * (1.0 + 0.15 * 23.659197), 1e-6);
    // Above Re ~ 1000 the constant Newton regime
    EXPECT_DOUBLE_EQ(schillerNaumannDragCoefficient(1000.0), 0.44);
    EXPECT_DOUBLE_EQ(schillerNaumannDragCoefficient(1e5), 0.44);
    // Stokes limit
    EXPECT_NEAR(schillerNaumannDragCoefficient(1e-6) * 1e-6 / 24.0, 1.0, 1e-4);
    EXPECT_THROW(schillerNaumannDragCoefficient(0.0), std::invalid_argument);
}


TEST(HydrostaticWater, DragOpposesVelocityAndScalesWithSubmergedFraction)
{
    const HydrostaticWater w(water());
    const double r = 0.01;
    const Vec3 v(0.1, -0.2, 0.05);
    const double speed = v.norm();
    const double reynolds = waterDensity * speed * 2 * r / waterViscosity;
    const double cd = std::max(0.44, 24.0 / reynolds * (1.0 + 0.15 * std::pow(reynolds, 0.687)));
    const Vec3 expected = -0.5 * waterDensity * cd * M_PI * r * r * speed * v;

    const SphereWaterLoad deep = w.sphereLoad(r, -1.0, v);
    EXPECT_NEAR((deep.drag - expected).norm(), 0.0, 1e-12 * expected.norm());

    const SphereWaterLoad half = w.sphereLoad(r, 0.0, v);
    EXPECT_NEAR((half.drag - 0.5 * expected).norm(), 0.0, 1e-12 * expected.norm());

    HydrostaticWaterParameters noDrag = water();
    noDrag.drag = false;
    EXPECT_EQ(HydrostaticWater(noDrag).sphereLoad(r, -1.0, v).drag, Vec3::Zero());
}


TEST(HydrostaticWater, RigidBodyBuoyancy)
{
    const HydrostaticWater w(water(0.8));
    // Platen 0.25 x 0.94 m, 0.1 m thick, 3 cm in the water.
    EXPECT_NEAR(w.submergedPrismVolume(0.25 * 0.94, 0.77, 0.87), 0.25 * 0.94 * 0.03, 1e-15);
    EXPECT_EQ(w.submergedPrismVolume(0.25 * 0.94, 0.81, 0.91), 0.0);
    EXPECT_NEAR(w.submergedPrismVolume(0.25 * 0.94, 0.2, 0.3), 0.25 * 0.94 * 0.1, 1e-15);
    EXPECT_NEAR(w.buoyancy(0.01), waterDensity * g * 0.01, 1e-12);

    // Horizontal cylinder: empty, half, full, and a slice integrated numerically.
    const double r = 0.075, length = 0.94;
    EXPECT_EQ(w.submergedHorizontalCylinderVolume(r, length, 0.8 + r), 0.0);
    EXPECT_NEAR(w.submergedHorizontalCylinderVolume(r, length, 0.8), 0.5 * M_PI * r * r * length, 1e-14);
    EXPECT_NEAR(w.submergedHorizontalCylinderVolume(r, length, 0.8 - r), M_PI * r * r * length, 1e-14);
    const double axis = 0.8 + 0.4 * r;   // water up to 0.6 r above the bottom
    double area = 0.0;
    const int n = 100000;
    const double top = 0.8 - axis, dz = (top + r) / n;
    for (int k = 0; k < n; ++k)
    {
        const double z = -r + (k + 0.5) * dz;
        area += 2.0 * std::sqrt(r * r - z * z) * dz;
    }
    EXPECT_NEAR(w.submergedHorizontalCylinderVolume(r, length, axis) / (area * length), 1.0, 1e-7);
}


namespace
{

//- One sphere under gravity and water, advanced as LIGGGHTS does it
//  (velocity Verlet, `fix nve/sphere`): half kick, drift, forces at the new
//  position with the half-step velocity (what post_force sees), the
//  implicit added mass, half kick.
struct VerletSphere
{
    const HydrostaticWater& water;
    double radius, mass;
    double z, v;
    double force = 0.0;

    void computeForce()
    {
        const SphereWaterLoad load = water.sphereLoad(radius, z, Vec3(0, 0, v));
        force = (-mass * water.parameters().gravity + load.buoyancy.z() + load.drag.z())
            * water.inertiaFactor(mass, load.addedMass);
    }

    void step(double dt)
    {
        v += 0.5 * dt * force / mass;
        z += dt * v;
        computeForce();
        v += 0.5 * dt * force / mass;
    }
};

//- Classical RK4 on y' = f(y) for a scalar: the accurate reference.
double rk4(const std::function<double(double)>& f, double y, double dt)
{
    const double k1 = f(y), k2 = f(y + 0.5 * dt * k1), k3 = f(y + 0.5 * dt * k2), k4 = f(y + dt * k3);
    return y + dt / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4);
}

//- Submerged sphere: (m + C_a rho_w V) dv/dt = (rho_w - rho_p) V g - 0.5 rho_w C_d(Re) pi r^2 |v| v,
//  written out here from the formulas, not through HydrostaticWater.
double submergedAcceleration(double r, double rhoP, double v)
{
    const double volume = sphereVolume(r);
    double force = (waterDensity - rhoP) * volume * g;
    if (v != 0.0)
    {
        const double re = waterDensity * std::abs(v) * 2 * r / waterViscosity;
        const double cd = std::max(0.44, 24.0 / re * (1.0 + 0.15 * std::pow(re, 0.687)));
        force -= 0.5 * waterDensity * cd * M_PI * r * r * std::abs(v) * v;
    }
    return force / ((rhoP + 0.5 * waterDensity) * volume);
}

void checkSettling(double r, double rhoP, double duration, double dt)
{
    const HydrostaticWater w(water(10.0));   // starts 9 m deep, never reaches the surface
    VerletSphere s{w, r, rhoP * sphereVolume(r), 1.0, 0.0};
    s.computeForce();

    double vRef = 0.0;
    const int substeps = 20;
    const int steps = static_cast<int>(std::lround(duration / dt));
    const double vTerminal = terminalVelocity(w, r, rhoP);
    double worstHistoryError = 0.0;
    for (int n = 0; n < steps; ++n)
    {
        s.step(dt);
        for (int k = 0; k < substeps; ++k)
        {
            vRef = rk4([&](double v) { return submergedAcceleration(r, rhoP, v); }, vRef, dt / substeps);
        }
        worstHistoryError = std::max(worstHistoryError, std::abs(s.v - vRef) / std::abs(vTerminal));
    }
    ASSERT_LT(s.z, 10.0 - r);
    // The velocity history follows the accurate ODE solution ...
    EXPECT_LT(worstHistoryError, 2e-3) << "r " << r << " rho_p " << rhoP;
    // ... and ends at the algebraic terminal velocity.
    EXPECT_NEAR(s.v / vTerminal, 1.0, 5e-3) << "r " << r << " rho_p " << rhoP;
    EXPECT_NEAR(vRef / vTerminal, 1.0, 1e-4) << "r " << r << " rho_p " << rhoP;

    // The terminal velocity balances net weight and drag (checked from the formulas).
    EXPECT_NEAR(submergedAcceleration(r, rhoP, vTerminal) * (rhoP + 0.5 * waterDensity) * sphereVolume(r)
                / ((waterDensity - rhoP) * sphereVolume(r) * g), 0.0, 1e-9);
}

} // namespace


TEST(SingleSphere, IceSphereRisesToTerminalVelocity)
{
    // 2 mm ice sphere: Re ~ 100, intermediate regime.
    checkSettling(0.001, 917.0, 1.0, 1e-4);
}


TEST(SingleSphere, HeavySphereSettlesToTerminalVelocity)
{
    // Ten Cate's 15 mm nylon sphere (1120 kg/m3) in water: Re ~ 2000, Newton regime.
    checkSettling(0.0075, 1120.0, 3.0, 1e-4);
    // A fine sand grain: near Stokes.
    checkSettling(5e-5, 2650.0, 0.02, 1e-6);
}


TEST(SingleSphere, VeryLightSphereRisesStablyWithImplicitAddedMass)
{
    // rho_p/rho_w = 0.05: added mass 10 times the sphere's own, where an
    // explicit added-mass force (-m_a times the last acceleration) would
    // multiply any error by -10 every step.
    checkSettling(0.001, 50.0, 0.5, 1e-4);
}


TEST(SingleSphere, TerminalVelocityInStokesLimit)
{
    // Re << 1: v = 2 (rho_p - rho_w) g r^2 / (9 mu) (1 + 0.15 Re^0.687 correction small).
    const HydrostaticWater w(water());
    const double r = 1e-5, rhoP = 1050.0;
    const double stokes = 2.0 * (rhoP - waterDensity) * g * r * r / (9.0 * waterViscosity);
    const double v = -terminalVelocity(w, r, rhoP);
    const double re = waterDensity * v * 2 * r / waterViscosity;
    EXPECT_NEAR(v / stokes, 1.0 / (1.0 + 0.15 * std::pow(re, 0.687)), 1e-9);
    EXPECT_LT(re, 1e-3);
}


TEST(FloatingSphere, DraftOfHalfDensitySphereIsItsRadius)
{
    EXPECT_NEAR(floatingSphereDraft(0.03, 500.0, 1000.0), 0.03, 1e-15);
    const double h = floatingSphereDraft(0.03, 917.0, 1000.0);
    EXPECT_NEAR(1000.0 * submergedSphereVolume(0.03, h) / (917.0 * sphereVolume(0.03)), 1.0, 1e-14);
    EXPECT_THROW(floatingSphereDraft(0.03, 1020.0, 1000.0), std::invalid_argument);
}


TEST(FloatingSphere, IceSphereDroppedOnTheWaterComesToRestAtItsDraft)
{
    // Released at rest touching the surface, it plunges, bobs, and is
    // brought to rest by drag alone.
    const HydrostaticWater w(water());
    const double r = 0.005, rhoP = 917.0, mass = rhoP * sphereVolume(r);
    const double draft = floatingSphereDraft(r, rhoP, waterDensity);
    VerletSphere s{w, r, mass, r, 0.0};
    s.computeForce();
    const double dt = 1e-3;
    double deepest = 0.0, worstDraftError = 0.0, worstKinetic = 0.0;
    for (int n = 0; n < 40000; ++n)
    {
        s.step(dt);
        const double d = r - s.z;   // depth of the lowest point
        deepest = std::max(deepest, d);
        if (n >= 39000)   // the last second
        {
            worstDraftError = std::max(worstDraftError, std::abs(d / draft - 1.0));
            worstKinetic = std::max(worstKinetic, 0.5 * mass * s.v * s.v);
        }
    }
    EXPECT_GT(deepest, 2.0 * r);   // it went right under first
    EXPECT_LT(worstDraftError, 0.01);
    // At rest: kinetic energy below 1e-6 of the energy scale m g r.
    EXPECT_LT(worstKinetic, 1e-6 * mass * g * r);
}


TEST(FloatingBlock, LevelDraftOfSphereLattices)
{
    // One sphere: the single-sphere draft.
    const double r = 0.0275;
    ParticleSpec one{Vec3(0.3, -0.2, 1.7), r};
    EXPECT_NEAR(levelDraft({one}, 0.917), floatingSphereDraft(r, 917.0, 1000.0), 1e-14);

    // Simple cubic stack of 4 layers (2 x 3 columns): 3.668 layers' volume
    // submerged, i.e. 3 whole layers and a cap x^2 (3 - 2x) = 0.668 of the
    // top one, x its submerged height over 2r; draft (3 + x) 2r.
    std::vector<ParticleSpec> block;
    for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 3; ++j)
            for (int k = 0; k < 4; ++k)
                block.push_back({Vec3(2 * r * i, 2 * r * j, 2 * r * k), r});
    double lo = 0.0, hi = 1.0;
    for (int n = 0; n < 100; ++n)
    {
        const double x = 0.5 * (lo + hi);
        (x * x * (3 - 2 * x) < 4 * 0.917 - 3 ? lo : hi) = x;
    }
    const double draft = levelDraft(block, 0.917);
    EXPECT_NEAR(draft, (3.0 + lo) * 2.0 * r, 1e-12);
    // ... which is not 0.917 of the height: the spheres' volume is bunched at
    // the layers' mid-planes.
    EXPECT_NEAR(draft / (8.0 * r), 0.9034, 1e-4);

    EXPECT_THROW(levelDraft(block, 1.02), std::invalid_argument);
}
