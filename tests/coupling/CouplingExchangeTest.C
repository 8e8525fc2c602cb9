// The coupling library on a 4 x 4 x 4 box of 0.1 m cells (unitMesh, made by
// blockMesh before these tests): particle volume and momentum are conserved
// between the particles and the cells, and bad set-ups are refused.
#include "particleFluidCoupling.H"
#include "couplingInterval.H"
#include "freeSurface.H"
#include "fvCFD.H"

#include <gtest/gtest.h>

#include <memory>
#include <random>

using namespace Foam;
using namespace Foam::iceCoupling;
using ::iceCoupling::CouplingParticle;

namespace
{

class CouplingExchange : public ::testing::Test
{
protected:
    static void SetUpTestSuite()
    {
        const fileName meshDir(COUPLING_UNIT_MESH);
        time_.reset(new Time(Time::controlDictName, fileName(meshDir.path()), fileName(meshDir.name())));
        mesh_.reset(new fvMesh(IOobject(fvMesh::defaultRegion, time_->timeName(), *time_,
                                        IOobject::MUST_READ)));
    }

    static void TearDownTestSuite()
    {
        mesh_.reset();
        time_.reset();
    }

    static const fvMesh& mesh() { return *mesh_; }

    static dictionary properties(const word& drag, const word& fraction, const word& momentum)
    {
        dictionary dict;
        dict.add("dragModel", drag);
        dict.add("fluidFractionModel", fraction);
        dict.add("momentumCoupling", momentum);
        return dict;
    }

    static volVectorField vectorField(const word& name, const vector& value)
    {
        return volVectorField
        (
            IOobject(name, time_->timeName(), *mesh_),
            *mesh_, dimensionedVector(name, dimVelocity, value), "calculated"
        );
    }

    //- n particles of diameter d, centres at least `margin` inside the 0.4 m box.
    static std::vector<CouplingParticle> randomParticles(int n, double d, double margin, unsigned seed)
    {
        std::mt19937 gen(seed);
        std::uniform_real_distribution<double> pos(margin, 0.4 - margin), vel(-0.2, 0.2);
        std::vector<CouplingParticle> particles;
        for (int i = 0; i < n; ++i)
        {
            particles.push_back({i + 1, {pos(gen), pos(gen), pos(gen)},
                                 {vel(gen), vel(gen), vel(gen)}, d});
        }
        return particles;
    }

    static double totalVolume(const std::vector<CouplingParticle>& particles)
    {
        double v = 0;
        for (const auto& p : particles)
        {
            v += constant::mathematical::pi/6*pow3(p.diameter);
        }
        return v;
    }

    static std::unique_ptr<Time> time_;
    static std::unique_ptr<fvMesh> mesh_;
};

std::unique_ptr<Time> CouplingExchange::time_;
std::unique_ptr<fvMesh> CouplingExchange::mesh_;

const scalar rho = 1000, nu = 1e-6;

//- Expects the next statement to stop with an OpenFOAM fatal error whose
//  message holds `expected`.
template<class Action>
void expectFatal(Action action, const std::string& expected)
{
    const bool previous = FatalError.throwExceptions();
    const bool previousIO = FatalIOError.throwExceptions();
    try
    {
        action();
        ADD_FAILURE() << "accepted; expected an error saying '" << expected << "'";
    }
    catch (const Foam::error& e)
    {
        const std::string msg = e.message();
        EXPECT_NE(msg.find(expected), std::string::npos) << msg;
    }
    FatalError.throwExceptions(previous);
    FatalIOError.throwExceptions(previousIO);
}

} // namespace


TEST_F(CouplingExchange, fluidFractionConservesParticleVolume)
{
    // Particles down to 5 mm from the walls: divided samples poke out of the
    // mesh there and must fall back to the centre's cell.
    const auto particles = randomParticles(200, 0.04, 0.005, 7);
    const auto U = vectorField("U", Zero);
    const auto gradp = vectorField("gradp", Zero);
    for (const label points : {1, 4, 9})   // 1: centre; divided with 4 and 9 points across
    {
        dictionary props(properties("DiFelice", points == 1 ? "centre" : "divided", "semiImplicit"));
        props.add("dividedPointsPerDiameter", points == 1 ? 4 : points);
        particleFluidCoupling coupling(mesh(), props, rho, nu);
        coupling.update(particles, U, gradp);
        EXPECT_EQ(coupling.clampedCells(), 0);
        const scalar solid = gSum((1 - coupling.alpha().primitiveField())*mesh().V());
        EXPECT_NEAR(solid/totalVolume(particles), 1.0, 1e-12) << points << " points across";
    }
}


TEST_F(CouplingExchange, dividedSharesAParticleBetweenTheCellsItOverlaps)
{
    // Centred on the corner shared by eight cells: one eighth in each.
    const std::vector<CouplingParticle> particles{{1, {0.2, 0.2, 0.2}, {0, 0, 0}, 0.06}};
    const auto U = vectorField("U", Zero);
    const auto gradp = vectorField("gradp", Zero);
    particleFluidCoupling coupling(mesh(), properties("DiFelice", "divided", "semiImplicit"), rho, nu);
    coupling.update(particles, U, gradp);
    const scalar eighth = totalVolume(particles)/8;
    label filled = 0;
    forAll(coupling.alpha(), celli)
    {
        const scalar solid = (1 - coupling.alpha()[celli])*mesh().V()[celli];
        if (solid > 0)
        {
            ++filled;
            EXPECT_NEAR(solid/eighth, 1.0, 1e-12);
        }
    }
    EXPECT_EQ(filled, 8);
}


TEST_F(CouplingExchange, meanParticleVelocityPerCell)
{
    // Two particles in one cell: the volume-weighted mean of their velocities.
    const std::vector<CouplingParticle> particles
    {
        {1, {0.05, 0.05, 0.05}, {1, 0, 0}, 0.02},
        {2, {0.06, 0.04, 0.05}, {0, 3, 0}, 0.04}
    };
    const auto U = vectorField("U", Zero);
    const auto gradp = vectorField("gradp", Zero);
    particleFluidCoupling coupling(mesh(), properties("DiFelice", "centre", "semiImplicit"), rho, nu);
    coupling.update(particles, U, gradp);
    const label celli = mesh().findCell(point(0.05, 0.05, 0.05));
    // Volumes in the ratio 1 : 8.
    EXPECT_NEAR(coupling.Us()[celli].x(), 1.0/9, 1e-14);
    EXPECT_NEAR(coupling.Us()[celli].y(), 24.0/9, 1e-14);
}


TEST_F(CouplingExchange, dragOnParticlesEqualAndOppositeToDragOnFluid)
{
    const auto particles = randomParticles(300, 0.03, 0.01, 11);
    auto U = vectorField("U", Zero);
    std::mt19937 gen(3);
    std::uniform_real_distribution<double> vel(-0.5, 0.5);
    for (vector& u : U.primitiveFieldRef())
    {
        u = vector(vel(gen), vel(gen), vel(gen));
    }
    const auto gradp = vectorField("gradp", vector(0, 0, -9.81));
    for (const word drag : {"SchillerNaumann", "DiFelice", "Beetstra"})
    {
        for (const word fraction : {"centre", "divided"})
        {
            particleFluidCoupling coupling(mesh(), properties(drag, fraction, "semiImplicit"), rho, nu);
            coupling.update(particles, U, gradp);
            const vector onParticles = coupling.totalDrag();
            const vector onFluid = coupling.fluidExchangeTotal(U);
            ASSERT_GT(mag(onParticles), 1e-6);
            EXPECT_LT(mag(onParticles + onFluid), 1e-12*mag(onParticles)) << drag << ' ' << fraction
                << ": particles " << onParticles.x() << ' ' << onParticles.y() << ' ' << onParticles.z()
                << ", fluid " << onFluid.x() << ' ' << onFluid.y() << ' ' << onFluid.z();
        }
    }
}


TEST_F(CouplingExchange, addedMassOpposesTheParticlesAcceleration)
{
    // Still fluid; between two updates (0.01 s apart) the particles' velocity
    // changes by dv: each feels -C_a rho V dv/dt, and the fluid gets its reaction.
    std::vector<CouplingParticle> particles = randomParticles(30, 0.03, 0.02, 13);
    const auto U = vectorField("U", Zero);
    const auto gradp = vectorField("gradp", Zero);
    dictionary props(properties("SchillerNaumann", "divided", "semiImplicit"));
    props.add("addedMassCoefficient", 0.5);
    const scalar couplingTime = 0.01;
    particleFluidCoupling coupling(mesh(), props, rho, nu, couplingTime);
    coupling.update(particles, U, gradp);
    EXPECT_EQ(mag(coupling.totalAddedMassForce()), 0.0);   // no history yet
    const vector dv(0.01, -0.02, 0.03);
    for (auto& p : particles)
    {
        for (int k = 0; k < 3; ++k) p.velocity[k] += dv[k];
    }
    coupling.update(particles, U, gradp);
    const scalar V = constant::mathematical::pi/6*pow3(0.03);
    const vector expected = -0.5*rho*V*dv/couplingTime*scalar(particles.size());
    EXPECT_LT(mag(coupling.totalAddedMassForce() - expected), 1e-12*mag(expected));
    // The fluid gets the reaction with the next exchange (same particles and
    // fluid here, so the same drag).
    const vector onParticles = coupling.totalDrag() + coupling.totalAddedMassForce();
    coupling.updateExchange(particles, U);
    EXPECT_LT(mag(onParticles + coupling.fluidExchangeTotal(U)), 1e-12*mag(onParticles));
}


TEST_F(CouplingExchange, momentumSourceDrivesTheFluidTowardsTheParticles)
{
    // Still fluid, particles moving in +x; one Euler step of dU/dt = source:
    // explicit gives dt KslUs, semi-implicit dt KslUs / (1 + dt Ksl).
    std::vector<CouplingParticle> particles = randomParticles(40, 0.05, 0.03, 5);
    for (auto& p : particles)
    {
        p.velocity = {0.3, 0, 0};
    }
    const scalar dt = 0.5;
    const auto gradp = vectorField("gradp", Zero);
    for (const word momentum : {"explicit", "semiImplicit"})
    {
        auto U = vectorField("U", Zero);
        U.oldTime();
        particleFluidCoupling coupling(mesh(), properties("DiFelice", "centre", momentum), rho, nu);
        coupling.update(particles, U, gradp);
        const_cast<Time&>(mesh().time()).setDeltaT(dt, false);
        fvVectorMatrix UEqn(fvm::ddt(U) == coupling.momentumSource(U));
        UEqn.solve();
        const scalarField& Ksl = coupling.Ksl();
        scalar checked = 0;
        forAll(U, celli)
        {
            const scalar KslUs = 0.3*Ksl[celli];
            const scalar expected = momentum == "explicit" ? dt*KslUs : dt*KslUs/(1 + dt*Ksl[celli]);
            EXPECT_NEAR(U[celli].x(), expected, 1e-12*(1 + mag(expected))) << momentum << " cell " << celli;
            checked += expected;
        }
        EXPECT_GT(checked, 0);
    }
}


TEST_F(CouplingExchange, pressureGradientGivesBuoyancy)
{
    // Still water (grad p = g): each resting particle feels rho V g upwards, no drag.
    std::vector<CouplingParticle> resting = randomParticles(20, 0.03, 0.02, 9);
    for (auto& p : resting)
    {
        p.velocity = {0, 0, 0};
    }
    const auto U = vectorField("U", Zero);
    const auto gradp = vectorField("gradp", vector(0, 0, -9.81));
    particleFluidCoupling coupling(mesh(), properties("SchillerNaumann", "divided", "semiImplicit"), rho, nu);
    coupling.update(resting, U, gradp);
    for (std::size_t i = 0; i < resting.size(); ++i)
    {
        const scalar weight = rho*constant::mathematical::pi/6*pow3(0.03)*9.81;
        EXPECT_NEAR(coupling.particleForces()[i][2]/weight, 1.0, 1e-12);
        EXPECT_EQ(coupling.particleForces()[i][0], 0.0);
    }
}


TEST_F(CouplingExchange, fluidFractionClampedToAlphaMin)
{
    // 25 particles of 40 mm in one 0.1 m cell leave alpha = 1 - 25 * 3.35e-5/1e-3 = 0.16.
    std::vector<CouplingParticle> particles;
    for (int i = 0; i < 25; ++i)
    {
        particles.push_back({i + 1, {0.05 + 0.001*i, 0.05, 0.05}, {0, 0, 0}, 0.04});
    }
    const auto U = vectorField("U", Zero);
    const auto gradp = vectorField("gradp", Zero);
    particleFluidCoupling coupling(mesh(), properties("DiFelice", "centre", "semiImplicit"), rho, nu);
    coupling.update(particles, U, gradp);
    EXPECT_EQ(coupling.clampedCells(), 1);
    EXPECT_DOUBLE_EQ(gMin(coupling.alpha().primitiveField()), coupling.alphaMin());
    EXPECT_DOUBLE_EQ(coupling.alphaMin(), 0.3);
}


TEST_F(CouplingExchange, particleOutsideTheMeshRefused)
{
    const std::vector<CouplingParticle> particles{{42, {0.5, 0.2, 0.2}, {0, 0, 0}, 0.01}};
    const auto U = vectorField("U", Zero);
    const auto gradp = vectorField("gradp", Zero);
    particleFluidCoupling coupling(mesh(), properties("DiFelice", "centre", "semiImplicit"), rho, nu);
    expectFatal([&] { coupling.update(particles, U, gradp); }, "particle 42 at (0.5 0.2 0.2) is outside the fluid mesh");
}


TEST_F(CouplingExchange, centreModelRefusesParticlesLargerThanCells)
{
    const std::vector<CouplingParticle> particles{{3, {0.2, 0.2, 0.2}, {0, 0, 0}, 0.12}};
    const auto U = vectorField("U", Zero);
    const auto gradp = vectorField("gradp", Zero);
    particleFluidCoupling coupling(mesh(), properties("DiFelice", "centre", "semiImplicit"), rho, nu);
    expectFatal([&] { coupling.update(particles, U, gradp); }, "Use fluidFractionModel divided");
}


TEST_F(CouplingExchange, unknownSubmodelNamesRefused)
{
    expectFatal([&] { particleFluidCoupling(mesh(), properties("DiFelice", "voronoi", "semiImplicit"), rho, nu); },
                "voronoi");
    expectFatal([&] { particleFluidCoupling(mesh(), properties("DiFelice", "centre", "implicit"), rho, nu); },
                "semiImplicit");
}


TEST_F(CouplingExchange, waterSurfaceGivesBuoyancyOfTheSubmergedCap)
{
    // Surface at the top of the box (z = 0.4 m); still water (grad p = g).
    // Centre at the surface: half the volume; 5 mm below with r = 10 mm: a cap
    // of height h = 15 mm, V_sub = pi h^2 (3r - h)/3; above by 20 mm: nothing.
    dictionary props(properties("SchillerNaumann", "centre", "semiImplicit"));
    props.add("waterLevel", 0.4);
    const scalar r = 0.01;
    const std::vector<CouplingParticle> particles
    {
        {1, {0.05, 0.05, 0.4}, {0, 0, 0}, 2*r},
        {2, {0.15, 0.05, 0.395}, {0, 0, 0}, 2*r},
        {3, {0.25, 0.05, 0.42}, {0, 0, 0}, 2*r},
        {4, {0.35, 0.05, 0.2}, {0, 0, 0}, 2*r}
    };
    const auto U = vectorField("U", Zero);
    const auto gradp = vectorField("gradp", vector(0, 0, -9.81));
    particleFluidCoupling coupling(mesh(), props, rho, nu);
    coupling.update(particles, U, gradp);
    const scalar V = 4.0/3*constant::mathematical::pi*pow3(r);
    const scalar h = 0.015;
    const scalar cap = constant::mathematical::pi*sqr(h)*(3*r - h)/3;
    const scalar expected[4] = {0.5*V, cap, 0, V};
    for (int i = 0; i < 4; ++i)
    {
        EXPECT_NEAR(coupling.particleForces()[i][2], rho*9.81*expected[i], 1e-12) << "particle " << i + 1;
    }
    // The fluid gets the submerged volumes.
    const scalar solid = gSum((1 - coupling.alpha().primitiveField())*mesh().V());
    EXPECT_NEAR(solid, 0.5*V + cap + V, 1e-15);
}


TEST_F(CouplingExchange, waterLevelBelowTheMeshTopRefused)
{
    dictionary props(properties("SchillerNaumann", "centre", "semiImplicit"));
    props.add("waterLevel", 0.3);
    expectFatal([&] { particleFluidCoupling(mesh(), props, rho, nu); }, "must end at the water surface");
}


TEST(CouplingInterval, fluidStepDividingTheCouplingTimeAccepted)
{
    dictionary dict;
    dict.add("couplingInterval", 50);
    const couplingInterval interval(dict, 1e-5, 2.5e-4);
    EXPECT_EQ(interval.demSteps(), 50);
    EXPECT_EQ(interval.fluidSteps(), 2);
    EXPECT_DOUBLE_EQ(interval.time(), 5e-4);
}


TEST(CouplingInterval, fluidStepNotDividingTheCouplingTimeRefused)
{
    dictionary dict;
    dict.add("couplingInterval", 50);
    expectFatal([&] { couplingInterval(dict, 1e-5, 3e-4); }, "does not divide");
    expectFatal([&] { couplingInterval(dict, 1e-5, 1e-3); }, "does not divide");
    dict.set("couplingInterval", 0);
    expectFatal([&] { couplingInterval(dict, 1e-5, 1e-5); }, "a whole number >= 1");
}


TEST_F(CouplingExchange, smoothingKeepsTheParticleVolumeAndSpreadsIt)
{
    // Particles clustered in one corner cell: smoothing over one cell width
    // must move volume into the neighbours without losing or making any.
    std::vector<CouplingParticle> particles;
    for (int i = 0; i < 27; ++i)
    {
        particles.push_back({i + 1, {0.02 + 0.03*(i % 3), 0.02 + 0.03*(i/3 % 3), 0.02 + 0.03*(i/9)},
                             {0, 0, 0}, 0.025});
    }
    const auto U = vectorField("U", Zero);
    const auto gradp = vectorField("gradp", Zero);
    const label corner = mesh().findCell(point(0.05, 0.05, 0.05));
    const label neighbour = mesh().findCell(point(0.15, 0.05, 0.05));
    scalar cornerUnsmoothed = 0;
    for (const scalar length : {0.0, 0.05, 0.1, 0.3})
    {
        dictionary props(properties("DiFelice", "divided", "semiImplicit"));
        props.add("smoothingLength", length);
        particleFluidCoupling coupling(mesh(), props, rho, nu);
        coupling.update(particles, U, gradp);
        const scalarField solid(1 - coupling.alpha().primitiveField());
        EXPECT_NEAR(gSum(solid*mesh().V())/totalVolume(particles), 1.0, 1e-10) << "L = " << length;
        EXPECT_GE(gMin(solid), -1e-12) << "L = " << length;
        if (length == 0)
        {
            cornerUnsmoothed = solid[corner];
            EXPECT_EQ(solid[neighbour], 0);
        }
        else
        {
            EXPECT_LT(solid[corner], cornerUnsmoothed) << "L = " << length;
            EXPECT_GT(solid[neighbour], 0) << "L = " << length;
        }
    }
}


TEST_F(CouplingExchange, negativeSmoothingLengthRefused)
{
    dictionary props(properties("DiFelice", "divided", "semiImplicit"));
    props.add("smoothingLength", -0.01);
    expectFatal([&]() { particleFluidCoupling coupling(mesh(), props, rho, nu); }, "smoothingLength");
}


// The vof level (iceInterFoam): water below z = 0.25 m, air above, in the
// 0.4 m box of 0.1 m cells.
namespace
{

volScalarField uniformField(const fvMesh& mesh, const word& name, const dimensionSet& dims, scalar value)
{
    return volScalarField
    (
        IOobject(name, mesh.time().timeName(), mesh), mesh, dimensionedScalar(name, dims, value),
        zeroGradientFvPatchScalarField::typeName
    );
}

} // namespace


TEST_F(CouplingExchange, vofFreeSurfaceSetsTheLevelAndReadsItBack)
{
    const freeSurface surface(mesh());
    volScalarField alphaWater(uniformField(mesh(), "alpha.water", dimless, 0));
    const volScalarField eps(uniformField(mesh(), "eps", dimless, 1));
    surface.setLevel(alphaWater, 0.25);
    EXPECT_NEAR(surface.planArea(), 0.16, 1e-14);
    EXPECT_NEAR(surface.waterVolume(alphaWater, eps), 0.16*0.25, 1e-14);
    EXPECT_NEAR(surface.freeLevel(alphaWater, eps), 0.25, 1e-14);
    const tmp<Foam::scalarField> height(surface.columnHeight(alphaWater));
    EXPECT_NEAR(gMin(height()), 0.25, 1e-14);
    EXPECT_NEAR(gMax(height()), 0.25, 1e-14);
    // The cell the surface cuts holds half water.
    EXPECT_NEAR(gMax(alphaWater.primitiveField()*(1 - alphaWater.primitiveField())), 0.25, 1e-14);
}


TEST_F(CouplingExchange, vofBuoyancyOfTheCapUnderTheColumnsWaterHeight)
{
    // Still water: no dynamic pressure gradient. Centre at the surface: half
    // the volume; 5 mm below with r = 10 mm: a cap 15 mm high; above by 20 mm:
    // nothing; deep: all of it. Drag: none at rest.
    const freeSurface surface(mesh());
    volScalarField alphaWater(uniformField(mesh(), "alpha.water", dimless, 0));
    surface.setLevel(alphaWater, 0.25);
    const volScalarField rhoMix("rho", alphaWater*dimensionedScalar("rw", dimDensity, 1000.0)
        + (1 - alphaWater)*dimensionedScalar("ra", dimDensity, 1.0));
    const volScalarField nuMix(uniformField(mesh(), "nu", dimViscosity, 1e-6));
    dictionary props(properties("SchillerNaumann", "divided", "semiImplicit"));
    props.add("verticalSharing", "linear");
    particleFluidCoupling coupling(mesh(), props, rho, nu);
    coupling.setMixture(rhoMix, nuMix, 1000, 9.81);
    const scalar r = 0.01;
    const std::vector<CouplingParticle> particles
    {
        {1, {0.05, 0.05, 0.25}, {0, 0, 0}, 2*r},
        {2, {0.15, 0.05, 0.245}, {0, 0, 0}, 2*r},
        {3, {0.25, 0.05, 0.27}, {0, 0, 0}, 2*r},
        {4, {0.35, 0.05, 0.1}, {0, 0, 0}, 2*r}
    };
    const auto U = vectorField("U", Zero);
    const auto gradpd = vectorField("gradpd", Zero);
    const tmp<Foam::scalarField> height(surface.columnHeight(alphaWater));
    coupling.updateFluidFraction(particles);
    coupling.updateExchange(particles, U);
    coupling.setWaterHeight(height());
    coupling.updateForces(particles, U, gradpd);
    const scalar V = 4.0/3*constant::mathematical::pi*pow3(r);
    const scalar h = 0.015;
    const scalar cap = constant::mathematical::pi*sqr(h)*(3*r - h)/3;
    const scalar expected[4] = {0.5*V, cap, 0, V};
    for (int i = 0; i < 4; ++i)
    {
        EXPECT_NEAR(coupling.particleForces()[i][2], 1000*9.81*expected[i], 1e-12) << "particle " << i + 1;
    }
    EXPECT_NEAR(coupling.totalSubmergedVolume(), expected[0] + expected[1] + expected[2] + expected[3], 1e-16);
    // The particles take their whole volume from the fluid, air or water.
    const scalar solid = gSum((1 - coupling.alpha().primitiveField())*mesh().V());
    EXPECT_NEAR(solid/(4*V), 1.0, 1e-12);
}


TEST_F(CouplingExchange, vofDragFromTheLocalMixture)
{
    // A particle in the air cells gets the drag of air, one in the water cells
    // that of water: each the same as at the cfd level in that fluid alone.
    const freeSurface surface(mesh());
    volScalarField alphaWater(uniformField(mesh(), "alpha.water", dimless, 0));
    surface.setLevel(alphaWater, 0.2);
    const volScalarField rhoMix("rho", alphaWater*dimensionedScalar("rw", dimDensity, 1000.0)
        + (1 - alphaWater)*dimensionedScalar("ra", dimDensity, 1.0));
    const volScalarField nuMix("nu", alphaWater*dimensionedScalar("nw", dimViscosity, 1e-6)
        + (1 - alphaWater)*dimensionedScalar("na", dimViscosity, 1.5e-5));
    const dictionary props(properties("SchillerNaumann", "centre", "semiImplicit"));
    const std::vector<CouplingParticle> inAir{{1, {0.05, 0.05, 0.35}, {0.1, 0, 0}, 0.01}};
    const std::vector<CouplingParticle> inWater{{1, {0.05, 0.05, 0.05}, {0.1, 0, 0}, 0.01}};
    const auto U = vectorField("U", Zero);
    const auto gradp = vectorField("gradp", Zero);
    const tmp<Foam::scalarField> height(surface.columnHeight(alphaWater));
    for (const auto& [particles, rhoAlone, nuAlone] :
         {std::make_tuple(inAir, 1.0, 1.5e-5), std::make_tuple(inWater, 1000.0, 1e-6)})
    {
        particleFluidCoupling vof(mesh(), props, rho, nu);
        vof.setMixture(rhoMix, nuMix, 1000, 9.81);
        vof.setWaterHeight(height());
        vof.update(particles, U, gradp);
        particleFluidCoupling alone(mesh(), props, rhoAlone, nuAlone);
        alone.update(particles, U, gradp);
        EXPECT_NEAR(vof.totalDrag().x()/alone.totalDrag().x(), 1.0, 1e-12) << "rho " << rhoAlone;
        // Equal and opposite on the fluid (per unit mass of the cell's mixture).
        EXPECT_NEAR(vof.fluidExchangeTotal(U).x()/vof.totalDrag().x(), -1.0, 1e-12);
    }
}


TEST_F(CouplingExchange, vofVerticalSharingMovesTheVolumeSmoothly)
{
    // A particle rising through the face at z = 0.2 m: with verticalSharing
    // linear the solid volume of the cell below falls linearly with the
    // particle's height (no jump at the face), the total is kept.
    dictionary props(properties("SchillerNaumann", "centre", "semiImplicit"));
    props.add("verticalSharing", "linear");
    particleFluidCoupling coupling(mesh(), props, rho, nu);
    const scalar d = 0.01, V = constant::mathematical::pi/6*pow3(d);
    const label below = mesh().findCell(point(0.05, 0.05, 0.15));
    for (const scalar z : {0.15, 0.175, 0.199999, 0.200001, 0.225, 0.25})
    {
        coupling.updateFluidFraction({{1, {0.05, 0.05, z}, {0, 0, 0}, d}});
        const Foam::scalarField solid((1 - coupling.alpha().primitiveField())*mesh().V());
        const scalar expectedBelow = V*min(max(0.5 - (z - 0.2)/0.1, 0.0), 1.0);
        EXPECT_NEAR(solid[below], expectedBelow, 1e-9*V) << "z = " << z;
        EXPECT_NEAR(sum(solid), V, 1e-15) << "z = " << z;
    }
}
