// A frozen reference of the bond law, in the style of LAMMPS' force-style
// tests: a fixed cluster of 13 bonded spheres (both bond families, every
// spring pre-loaded, compression as well as tension, four leaves driven to
// break in tension, shear, twist and bending, freeze-bonds under the combined
// criterion) is stepped 100 times under each damping model, and the forces
// and torques on every particle and every bond's histories, break mode and
// break step at steps 0 and 100 are compared with tests/unit/data/
// bondKernelReference.txt. The other kernel tests compare the batch kernel
// with BondModel, which runs the same kernel body: a change to that body
// shows only here.
//
// The loads are computed as IceBondForces does on one rank (bonds sorted by
// their atoms, in batches of bondKernelLanes with a padded last batch, each
// bond's loads in its atoms' slots summed by partner tag, hysteretic damping
// on the sums, breakage tested on the lanes the kernel flags), once with each
// kernel this processor runs, and once with BondModel::evaluate bond by bond.
// The particles move by velocity Verlet as in LIGGGHTS' fix nve/sphere.
//
// Tolerance: 1e-12 relative; a value below 1 % of the largest of its kind
// (force, torque, shear displacement, ...) in its snapshot is compared to
// 1e-12 of that 1 %, i.e. 1e-14 of the largest, since it comes from the
// cancellation of terms of that size. Break modes and steps must match exactly.
//
// To rewrite the file from the current code (after an intended change of the
// law; say why in the commit):
//   ICEDEM_REGENERATE_REFERENCE=1 build/tests/unitTests --gtest_filter='BondKernelReference.*'

#include "BondBatches.H"
#include "BondKernel.H"
#include "BondModel.H"
#include "HystereticDamping.H"
#include "IceProperties.H"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <initializer_list>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

using namespace iceDEM;

namespace
{

const std::string referencePath = ICEDEM_SOURCE_DIR "/tests/unit/data/bondKernelReference.txt";
constexpr double dt = 2e-6;
constexpr int steps = 100;
constexpr double density = 917.0;

// ---------------------------------------------------------------- the scene

//- Block A: a triangular layer (0-5); block B: three spheres in its hollows
//  (6-8); four leaves (9-12), each on its own so that its bond's break is the
//  one it was set up for.
struct ParticleRow
{
    double position[3], velocity[3], angularVelocity[3], radius;
};

const ParticleRow particleRows[] =
{
    //  position                      velocity (m/s)             spin (rad/s)            radius
    {{ 0.0000,  0.0000,  0.0000}, { 0.031, -0.012,  0.020}, { 1.3, -0.7,  2.1}, 0.0200},
    {{ 0.0403,  0.0004, -0.0003}, {-0.024,  0.017, -0.009}, {-0.8,  1.9, -1.2}, 0.0207},
    {{ 0.0806, -0.0002,  0.0005}, { 0.015,  0.028, -0.033}, { 2.4,  0.6, -0.5}, 0.0196},
    {{ 0.0198,  0.0351,  0.0002}, {-0.019, -0.027,  0.014}, {-1.7, -2.2,  0.9}, 0.0192},
    {{ 0.0601,  0.0347, -0.0004}, { 0.022, -0.008,  0.026}, { 0.4,  1.1,  1.8}, 0.0211},
    {{ 0.0399,  0.0702,  0.0003}, {-0.013,  0.035, -0.018}, {-2.6,  0.3, -1.4}, 0.0188},
    {{ 0.0202,  0.0119,  0.0330}, { 0.210,  0.120,  0.330}, { 1.0, -1.6,  0.7}, 0.0203},
    {{ 0.0601,  0.0114,  0.0326}, {-0.029,  0.011,  0.016}, {-0.9,  2.3, -0.6}, 0.0194},
    {{ 0.0398,  0.0469,  0.0331}, { 0.017, -0.021, -0.025}, { 1.5,  0.8,  2.7}, 0.0209},
    {{-0.0395,  0.0003, -0.0002}, {-1.000,  0.013,  0.009}, { 0.5, -0.4,  0.6}, 0.0197},  // pulled off: tension
    {{ 0.1204,  0.0001,  0.0004}, { 0.012, -3.000,  0.008}, {-0.3,  0.7, -0.2}, 0.0202},  // slid off: shear
    {{ 0.0401,  0.1100,  0.0002}, { 0.011, -0.014,  0.010}, { 0.4, 120.0, -0.5}, 0.0199},  // spun about its bond: twist
    {{ 0.0603,  0.0116,  0.0722}, {-0.010,  0.012, -0.009}, {-80.0, 0.3,  0.6}, 0.0201},  // spun across it: bending
};

//- A bond and its pre-load, each component as a signed fraction of its limit
//  under the separate criterion (stretch: tension positive).
struct BondRow
{
    int a, b;
    BondFamily family;
    double stretch, shear, twist, bending;
    double tensileStrength;   // freeze-bonds' own (perBond); shear strength 0.8 of it
};

const BondRow bondRows[] =
{
    {0, 1, BondFamily::ice, 0.3, 0.2, 0.1, 0.2, 0.0},
    {1, 2, BondFamily::ice, -0.4, 0.1, -0.2, 0.1, 0.0},
    {0, 3, BondFamily::ice, 0.1, -0.3, 0.2, -0.1, 0.0},
    {1, 3, BondFamily::ice, -0.2, 0.2, 0.1, 0.3, 0.0},
    {1, 4, BondFamily::ice, 0.2, 0.1, -0.1, -0.2, 0.0},
    {2, 4, BondFamily::ice, -0.5, 0.3, 0.2, 0.1, 0.0},
    {3, 4, BondFamily::ice, 0.4, -0.1, 0.3, 0.2, 0.0},
    {3, 5, BondFamily::ice, 0.1, 0.2, -0.3, -0.2, 0.0},
    {4, 5, BondFamily::ice, -0.3, -0.2, 0.1, 0.3, 0.0},
    {6, 7, BondFamily::ice, 0.2, 0.1, 0.1, 0.1, 0.0},
    {6, 8, BondFamily::ice, -0.3, 0.2, -0.1, 0.2, 0.0},
    {7, 8, BondFamily::ice, 0.1, -0.2, 0.2, -0.1, 0.0},
    {0, 6, BondFamily::freeze, 0.45, 0.1, 0.05, 0.09, 9.0e4},
    {3, 6, BondFamily::freeze, 0.1, 0.1, 0.1, 0.05, 1.2e5},
    {2, 7, BondFamily::freeze, -0.2, 0.15, 0.05, 0.05, 1.5e5},
    {4, 7, BondFamily::freeze, 0.2, -0.1, 0.05, 0.05, 1.1e5},
    {5, 8, BondFamily::freeze, 0.1, 0.1, -0.05, 0.05, 1.3e5},
    {0, 9, BondFamily::ice, 0.8, 0.1, 0.1, 0.1, 0.0},
    {2, 10, BondFamily::ice, 0.1, 0.9, 0.1, 0.1, 0.0},
    {5, 11, BondFamily::ice, 0.1, 0.1, 0.9, 0.1, 0.0},
    {7, 12, BondFamily::ice, 0.1, 0.1, 0.1, 0.8, 0.0},
};

IceProperties sceneProperties(DampingModel damping)
{
    IceProperties props;
    BondFamilyParameters& ice = props.families[static_cast<int>(BondFamily::ice)];
    ice.youngsModulus = 5.4e7;
    ice.poissonsRatio = 0.3;
    ice.radiusMultiplier = 0.9;
    ice.strengthModel = StrengthModel::strain;
    ice.breakN = 0.0037;
    ice.beta = 1.25;
    ice.twistStrengthFactor = 0.25;
    ice.bendingStrengthFactor = 0.3;
    ice.criterion = BreakageCriterion::separate;
    BondFamilyParameters& freeze = props.families[static_cast<int>(BondFamily::freeze)];
    freeze.youngsModulus = 2.0e7;
    freeze.poissonsRatio = 0.33;
    freeze.radiusMultiplier = 0.6;
    freeze.strengthModel = StrengthModel::perBond;
    freeze.twistStrengthFactor = 0.8;
    freeze.bendingStrengthFactor = 0.7;
    freeze.criterion = BreakageCriterion::combined;
    props.damping.model = damping;
    props.damping.alpha = 0.15;
    props.damping.dampingRatio = 0.2;
    return props;
}

struct Scene
{
    IceProperties props;
    std::vector<ParticleState> particles;
    std::vector<BondState> bonds;   // sorted by (a, b), as IceBondForces lists them; tag = index + 1
};

Vec3 toVec3(const double v[3])
{
    return Vec3(v[0], v[1], v[2]);
}

//- A unit vector across n, the same for every run.
Vec3 tangentOf(const Vec3& n)
{
    const Vec3 reference = std::abs(n.z()) < 0.9 ? Vec3(0.0, 0.0, 1.0) : Vec3(1.0, 0.0, 0.0);
    return n.cross(reference).normalized();
}

void preload(BondState& s, const BondRow& row, const BondFamilyParameters& family, const BondStiffness& k, const Vec3& n)
{
    const double sigmaT = s.tensileStrength, tau = s.shearStrength;
    const Vec3 t = tangentOf(n);
    s.restLength -= row.stretch * sigmaT * k.area / k.normal;
    s.shearDisplacement = row.shear * tau * k.area / k.shear * t;
    s.twistAngle = row.twist * family.twistStrengthFactor * tau * k.area15 / k.twist;
    s.bendingAngle = row.bending * family.bendingStrengthFactor * sigmaT * k.area15 / k.bending * n.cross(t);
}

Scene referenceScene(DampingModel damping)
{
    Scene scene;
    scene.props = sceneProperties(damping);
    for (const ParticleRow& row : particleRows)
    {
        ParticleState p;
        p.position = toVec3(row.position);
        p.velocity = toVec3(row.velocity);
        p.angularVelocity = toVec3(row.angularVelocity);
        p.radius = row.radius;
        p.mass = density * 4.0 / 3.0 * M_PI * row.radius * row.radius * row.radius;
        scene.particles.push_back(p);
    }
    for (const BondRow& row : bondRows)
    {
        const BondFamilyParameters& family = scene.props.family(row.family);
        const BondModel model(family, scene.props.damping);
        const ParticleState& a = scene.particles[row.a];
        const ParticleState& b = scene.particles[row.b];
        BondState s = model.create(row.a + 1, row.b + 1, a, b);
        s.family = row.family;
        if (family.strengthModel == StrengthModel::perBond)
        {
            s.tensileStrength = row.tensileStrength;
            s.shearStrength = 0.8 * row.tensileStrength;
        }
        preload(s, row, family, BondStiffness::of(family, a.radius, b.radius), (b.position - a.position).normalized());
        scene.bonds.push_back(s);
    }
    std::sort(scene.bonds.begin(), scene.bonds.end(), [](const BondState& x, const BondState& y)
    {
        return std::tie(x.tagA, x.tagB) < std::tie(y.tagA, y.tagB);
    });
    return scene;
}

int indexOf(long tag)
{
    return static_cast<int>(tag) - 1;
}

// ----------------------------------------------------------- what is recorded

struct ParticleRecord
{
    long tag;
    Vec3 force, torque;
};

struct BondRecord
{
    long tagA = 0, tagB = 0;
    BondFamily family = BondFamily::ice;
    BreakMode broke = BreakMode::none;
    int brokeAtStep = -1;
    Vec3 centre = Vec3::Zero();   // where the springs act, and the histories, at the last step the bond acted
    Vec3 shearDisplacement = Vec3::Zero();
    double twistAngle = 0.0;
    Vec3 bendingAngle = Vec3::Zero();
};

struct Snapshot
{
    int step;
    std::vector<ParticleRecord> particles;
    std::vector<BondRecord> bonds;
};

//- Per damping model: the snapshots at step 0 and step `steps`.
using Reference = std::map<std::string, std::vector<Snapshot>>;

// ------------------------------------------------------- the two ways to step

//- Each particle's load slots, ordered by partner tag as IceBondForces orders
//  them (its sums must not depend on the bonds' order); a last slot takes the
//  loads nobody sums.
struct SlotLayout
{
    std::vector<int> firstOfParticle;   // size particles + 1
    std::vector<int> slotOfA, slotOfB;  // per bond
    int unsummed;

    SlotLayout(const std::vector<BondState>& bonds, int particles)
    {
        std::vector<std::vector<std::pair<long, int>>> ends(particles);   // (partner tag, 2 bond + (end is b))
        for (std::size_t k = 0; k < bonds.size(); ++k)
        {
            ends[indexOf(bonds[k].tagA)].push_back({bonds[k].tagB, 2 * static_cast<int>(k)});
            ends[indexOf(bonds[k].tagB)].push_back({bonds[k].tagA, 2 * static_cast<int>(k) + 1});
        }
        firstOfParticle.push_back(0);
        slotOfA.resize(bonds.size());
        slotOfB.resize(bonds.size());
        for (auto& own : ends)
        {
            std::sort(own.begin(), own.end());
            for (std::size_t n = 0; n < own.size(); ++n)
            {
                const int end = own[n].second;
                (end % 2 ? slotOfB : slotOfA)[end / 2] = firstOfParticle.back() + static_cast<int>(n);
            }
            firstOfParticle.push_back(firstOfParticle.back() + static_cast<int>(own.size()));
        }
        unsummed = firstOfParticle.back();
    }
};

//- Each particle's bond loads summed slot by slot, then hysteretic damping on
//  the sums, as IceBondForces::sumLoads does (here with no contact or gravity
//  loads to start from).
void sumLoads
(
    const std::vector<BondEndLoad>& slots, const SlotLayout& layout, const std::vector<ParticleState>& particles,
    const DampingParameters& damping, std::vector<Vec3>& force, std::vector<Vec3>& torque
)
{
    for (std::size_t i = 0; i < particles.size(); ++i)
    {
        Vec3 f = Vec3::Zero(), m = Vec3::Zero();
        for (int n = layout.firstOfParticle[i]; n < layout.firstOfParticle[i + 1]; ++n)
        {
            for (int c = 0; c < 3; ++c)
            {
                f[c] += slots[n].force[c];
                m[c] += slots[n].moment[c];
            }
        }
        if (damping.model == DampingModel::hysteretic && damping.alpha > 0.0)
        {
            applyHystereticDamping(f, particles[i].velocity, damping.alpha);
            applyHystereticDamping(m, particles[i].angularVelocity, damping.alpha);
        }
        force[i] = f;
        torque[i] = m;
    }
}

class BondStepper
{
public:
    virtual ~BondStepper() = default;
    virtual void computeLoads
    (
        const std::vector<ParticleState>&, int step, std::vector<Vec3>& force, std::vector<Vec3>& torque
    ) = 0;
    virtual std::vector<BondRecord> bondRecords() const = 0;
};

std::array<BondModel, nBondFamilies> modelsOf(const IceProperties& props)
{
    return {BondModel(props.family(BondFamily::ice), props.damping), BondModel(props.family(BondFamily::freeze), props.damping)};
}

//- The bonds' records before their first step.
std::vector<BondRecord> recordsOf(const std::vector<BondState>& bonds)
{
    std::vector<BondRecord> records;
    for (const BondState& s : bonds)
    {
        BondRecord r;
        r.tagA = s.tagA;
        r.tagB = s.tagB;
        r.family = s.family;
        records.push_back(r);
    }
    return records;
}

//- The production path: the batch kernel as IceBondForces drives it.
class BatchKernelStepper : public BondStepper
{
public:
    BatchKernelStepper(const Scene& scene, BondKernel kernel)
    :
        props_(scene.props),
        models_(modelsOf(scene.props)),
        bonds_(scene.bonds),
        layout_(scene.bonds, static_cast<int>(scene.particles.size())),
        kernel_(kernel),
        slots_(layout_.unsummed + 1),
        records_(recordsOf(scene.bonds))
    {
        batches_.resize(bonds_.size());
        for (std::size_t k = 0; k < bonds_.size(); ++k)
        {
            const BondModel& model = modelOf(k);
            const BondState& s = bonds_[k];
            stiffnesses_.push_back(BondStiffness::of(model.parameters(), scene.particles[indexOf(s.tagA)].radius,
                                                     scene.particles[indexOf(s.tagB)].radius));
            batches_.set(k, indexOf(s.tagA), indexOf(s.tagB), s, stiffnesses_[k], model.intactBounds(s, stiffnesses_[k]));
        }
        batches_.pad();
        for (std::size_t k = 0; k < batches_.batches() * bondKernelLanes; ++k)
        {
            const bool padding = k >= bonds_.size();
            batches_.setLoadSlots(k, padding ? layout_.unsummed : layout_.slotOfA[k],
                                  padding ? layout_.unsummed : layout_.slotOfB[k]);
        }
    }

    void computeLoads
    (
        const std::vector<ParticleState>& particles, int step, std::vector<Vec3>& force, std::vector<Vec3>& torque
    ) override
    {
        std::vector<KernelAtom> atoms;
        for (const ParticleState& p : particles)
        {
            atoms.push_back(kernelAtomOf(p));
        }
        BondKernelSettings settings;
        settings.dt = dt;
        settings.viscous = props_.damping.model == DampingModel::viscous && props_.damping.dampingRatio > 0.0;
        settings.dampingRatio = props_.damping.dampingRatio;
        BondKernelResult result;
        for (std::size_t j = 0; j < batches_.batches(); ++j)
        {
            const int mayBreak = kernel_(atoms.data(), batches_.batch(j), slots_.data(), settings, result);
            for (std::size_t k = j * bondKernelLanes; k < std::min((j + 1) * bondKernelLanes, bonds_.size()); ++k)
            {
                const int lane = static_cast<int>(k % bondKernelLanes);
                if (records_[k].broke != BreakMode::none)
                {
                    continue;
                }
                recordStep(k, result, lane);
                if (mayBreak >> lane & 1)
                {
                    breakIfOverLimit(k, result, lane, step);
                }
            }
        }
        sumLoads(slots_, layout_, particles, props_.damping, force, torque);
    }

    std::vector<BondRecord> bondRecords() const override { return records_; }

private:
    const BondModel& modelOf(std::size_t k) const { return models_[static_cast<int>(bonds_[k].family)]; }

    void recordStep(std::size_t k, const BondKernelResult& result, int lane)
    {
        BondState s = bonds_[k];
        batches_.copyHistory(k, s);
        BondRecord& r = records_[k];
        r.centre = Vec3(result.centre[0][lane], result.centre[1][lane], result.centre[2][lane]);
        r.shearDisplacement = s.shearDisplacement;
        r.twistAngle = s.twistAngle;
        r.bendingAngle = s.bendingAngle;
    }

    //- IceBondForces::breakIfOverLimit: the broken bond's slots give -0 from now on.
    void breakIfOverLimit(std::size_t k, const BondKernelResult& result, int lane, int step)
    {
        const BreakMode broke = modelOf(k).breakMode
        (
            bonds_[k], stiffnesses_[k], result.springNormalForce[lane],
            result.shearForce2[lane], result.twistTorque2[lane], result.bendingTorque2[lane]
        );
        if (broke == BreakMode::none)
        {
            return;
        }
        records_[k].broke = broke;
        records_[k].brokeAtStep = step;
        const BondEndLoad none{{-0.0, -0.0, -0.0}, {-0.0, -0.0, -0.0}};
        slots_[batches_.loadOfA(k)] = none;
        slots_[batches_.loadOfB(k)] = none;
        batches_.setLoadSlots(k, layout_.unsummed, layout_.unsummed);
    }

    IceProperties props_;
    std::array<BondModel, nBondFamilies> models_;
    std::vector<BondState> bonds_;   // tags, family, strengths; the histories run in batches_
    SlotLayout layout_;
    BondKernel kernel_;
    BondBatches batches_;
    std::vector<BondStiffness> stiffnesses_;
    std::vector<BondEndLoad> slots_;
    std::vector<BondRecord> records_;
};

//- The single-bond model, bond by bond, its loads summed in the same order.
class SingleBondStepper : public BondStepper
{
public:
    explicit SingleBondStepper(const Scene& scene)
    :
        props_(scene.props),
        models_(modelsOf(scene.props)),
        bonds_(scene.bonds),
        layout_(scene.bonds, static_cast<int>(scene.particles.size())),
        slots_(layout_.unsummed + 1),
        records_(recordsOf(scene.bonds))
    {}

    void computeLoads
    (
        const std::vector<ParticleState>& particles, int step, std::vector<Vec3>& force, std::vector<Vec3>& torque
    ) override
    {
        for (std::size_t k = 0; k < bonds_.size(); ++k)
        {
            BondState& s = bonds_[k];
            BondRecord& r = records_[k];
            if (r.broke != BreakMode::none)
            {
                continue;
            }
            const BondModel& model = models_[static_cast<int>(s.family)];
            const BondLoad load = model.evaluate(s, particles[indexOf(s.tagA)], particles[indexOf(s.tagB)], dt);
            r.centre = load.centre;
            r.shearDisplacement = s.shearDisplacement;
            r.twistAngle = s.twistAngle;
            r.bendingAngle = s.bendingAngle;
            if (load.broke != BreakMode::none)
            {
                r.broke = load.broke;
                r.brokeAtStep = step;
            }
            slots_[layout_.slotOfA[k]] = endLoad(load.forceOnA, load.torqueOnA);
            slots_[layout_.slotOfB[k]] = endLoad(-load.forceOnA, load.torqueOnB);
        }
        sumLoads(slots_, layout_, particles, props_.damping, force, torque);
    }

    std::vector<BondRecord> bondRecords() const override { return records_; }

private:
    static BondEndLoad endLoad(const Vec3& force, const Vec3& moment)
    {
        return {{force[0], force[1], force[2]}, {moment[0], moment[1], moment[2]}};
    }

    IceProperties props_;
    std::array<BondModel, nBondFamilies> models_;
    std::vector<BondState> bonds_;
    SlotLayout layout_;
    std::vector<BondEndLoad> slots_;
    std::vector<BondRecord> records_;
};

// ------------------------------------------------------------------ the run

Snapshot snapshotOf
(
    int step, const std::vector<Vec3>& force, const std::vector<Vec3>& torque, const BondStepper& stepper
)
{
    Snapshot s{step, {}, stepper.bondRecords()};
    for (std::size_t i = 0; i < force.size(); ++i)
    {
        s.particles.push_back({static_cast<long>(i) + 1, force[i], torque[i]});
    }
    return s;
}

//- Velocity Verlet as LIGGGHTS' fix nve/sphere (solid spheres); step 0 is
//  the set-up's force computation.
std::vector<Snapshot> run(std::vector<ParticleState> particles, BondStepper& stepper)
{
    const std::size_t n = particles.size();
    std::vector<Vec3> force(n), torque(n);
    auto halfKick = [&]()
    {
        for (std::size_t i = 0; i < n; ++i)
        {
            ParticleState& p = particles[i];
            p.velocity += 0.5 * dt * force[i] / p.mass;
            p.angularVelocity += 0.5 * dt * torque[i] / (0.4 * p.mass * p.radius * p.radius);
        }
    };
    stepper.computeLoads(particles, 0, force, torque);
    std::vector<Snapshot> snapshots{snapshotOf(0, force, torque, stepper)};
    for (int step = 1; step <= steps; ++step)
    {
        halfKick();
        for (ParticleState& p : particles)
        {
            p.position += dt * p.velocity;
        }
        stepper.computeLoads(particles, step, force, torque);
        halfKick();
    }
    snapshots.push_back(snapshotOf(steps, force, torque, stepper));
    return snapshots;
}

const DampingModel dampingModels[] = {DampingModel::none, DampingModel::hysteretic, DampingModel::viscous};

template<class MakeStepper>
Reference compute(MakeStepper makeStepper)
{
    Reference reference;
    for (DampingModel damping : dampingModels)
    {
        const Scene scene = referenceScene(damping);
        const std::unique_ptr<BondStepper> stepper = makeStepper(scene);
        reference[toString(damping)] = run(scene.particles, *stepper);
    }
    return reference;
}

Reference computeWithKernel(BondKernel kernel)
{
    return compute([kernel](const Scene& scene) { return std::make_unique<BatchKernelStepper>(scene, kernel); });
}

Reference computeWithBondModel()
{
    return compute([](const Scene& scene) { return std::make_unique<SingleBondStepper>(scene); });
}

// ------------------------------------------------------------ the data file

std::string commandOutput(const std::string& command)
{
    std::string out;
    if (FILE* pipe = popen(command.c_str(), "r"))
    {
        char buffer[256];
        while (std::fgets(buffer, sizeof buffer, pipe))
        {
            out += buffer;
        }
        pclose(pipe);
    }
    while (!out.empty() && out.back() == '\n')
    {
        out.pop_back();
    }
    return out;
}

std::string sourceVersion()
{
    const std::string git = "git -C '" ICEDEM_SOURCE_DIR "' ";
    const std::string commit = commandOutput(git + "rev-parse --short HEAD 2>/dev/null");
    const bool dirty = !commandOutput(git + "status --porcelain --untracked-files=no 2>/dev/null").empty();
    return (commit.empty() ? "unknown" : commit) + (dirty ? " with uncommitted changes" : "");
}

std::string format(double x)
{
    char text[32];
    std::snprintf(text, sizeof text, "%.17g", x);
    return text;
}

std::string format(const Vec3& v)
{
    return format(v[0]) + " " + format(v[1]) + " " + format(v[2]);
}

void write(const Reference& reference, const std::string& path)
{
    std::ofstream out(path);
    out << "# Frozen results of the bond law for tests/unit/BondKernelReferenceTest.C (the scene is there).\n"
        << "# Made by: ICEDEM_REGENERATE_REFERENCE=1 build/tests/unitTests --gtest_filter='BondKernelReference.*'\n"
        << "# from commit " << sourceVersion() << ", with the generic (SSE2) batch kernel.\n"
        << "# dt " << dt << " s; per damping model, at step 0 (the set-up's loads) and step " << steps << ":\n"
        << "#   particle TAG force FX FY FZ torque TX TY TZ   (N, N m: the bonds' loads after damping)\n"
        << "#   bond TAGA TAGB FAMILY BROKE BROKE_AT_STEP centre X Y Z shear UX UY UZ twist PHI bending BX BY BZ\n"
        << "#     (BROKE: none or the break mode; centre and histories (m, rad) at the last step the bond acted)\n";
    for (const auto& [damping, snapshots] : reference)
    {
        out << "damping " << damping << "\n";
        for (const Snapshot& s : snapshots)
        {
            out << "step " << s.step << "\n";
            for (const ParticleRecord& p : s.particles)
            {
                out << "particle " << p.tag << " force " << format(p.force) << " torque " << format(p.torque) << "\n";
            }
            for (const BondRecord& b : s.bonds)
            {
                out << "bond " << b.tagA << " " << b.tagB << " " << toString(b.family) << " " << toString(b.broke)
                    << " " << b.brokeAtStep << " centre " << format(b.centre) << " shear " << format(b.shearDisplacement)
                    << " twist " << format(b.twistAngle) << " bending " << format(b.bendingAngle) << "\n";
            }
        }
    }
}

template<class Enum>
Enum enumFrom(const std::string& name, std::initializer_list<Enum> values)
{
    for (Enum e : values)
    {
        if (toString(e) == name)
        {
            return e;
        }
    }
    throw std::runtime_error("unknown name '" + name + "' in " + referencePath);
}

Vec3 readVec3(std::istream& in)
{
    Vec3 v;
    in >> v[0] >> v[1] >> v[2];
    return v;
}

Reference read(const std::string& path)
{
    std::ifstream in(path);
    if (!in)
    {
        throw std::runtime_error("cannot read " + path);
    }
    Reference reference;
    std::vector<Snapshot>* snapshots = nullptr;
    std::string line;
    while (std::getline(in, line))
    {
        std::istringstream words(line);
        std::string key, label;
        words >> key;
        if (key == "damping")
        {
            words >> label;
            snapshots = &reference[label];
        }
        else if (key == "step")
        {
            snapshots->push_back({});
            words >> snapshots->back().step;
        }
        else if (key == "particle")
        {
            ParticleRecord p;
            words >> p.tag >> label;
            p.force = readVec3(words);
            words >> label;
            p.torque = readVec3(words);
            snapshots->back().particles.push_back(p);
        }
        else if (key == "bond")
        {
            BondRecord b;
            std::string family, broke;
            words >> b.tagA >> b.tagB >> family >> broke >> b.brokeAtStep >> label;
            b.family = enumFrom(family, {BondFamily::ice, BondFamily::freeze});
            b.broke = enumFrom(broke, {BreakMode::none, BreakMode::tension, BreakMode::shear, BreakMode::twist, BreakMode::bending});
            b.centre = readVec3(words);
            words >> label;
            b.shearDisplacement = readVec3(words);
            words >> label >> b.twistAngle >> label;
            b.bendingAngle = readVec3(words);
            snapshots->back().bonds.push_back(b);
        }
    }
    return reference;
}

// ------------------------------------------------------------ the comparison

constexpr double relativeTolerance = 1e-12;
constexpr double floorFraction = 0.01;   // of the largest value of the same kind in the snapshot

//- Collects the mismatches of one comparison and reports the first few.
class Mismatches
{
public:
    explicit Mismatches(std::string what) : what_(std::move(what)) {}

    ~Mismatches()
    {
        if (count_ > 0)
        {
            ADD_FAILURE() << what_ << ": " << count_ << " values differ from " << referencePath << ":\n"
                          << report_ << (count_ > shown ? "  ...\n" : "");
        }
    }

    void add(const std::string& mismatch)
    {
        if (++count_ <= shown)
        {
            report_ += "  " + mismatch + "\n";
        }
    }

private:
    static constexpr int shown = 12;
    std::string what_, report_;
    int count_ = 0;
};

//- The values of one kind (force, torque, ...) in a snapshot, and their scale.
struct Quantity
{
    std::string name;
    std::vector<std::string> where, component;   // "particle 3", "x" ("" for a scalar)
    std::vector<double> computed, expected;

    void add(const std::string& place, const std::string& axis, double value, double reference)
    {
        where.push_back(place);
        component.push_back(axis);
        computed.push_back(value);
        expected.push_back(reference);
    }

    void compare(const std::string& context, Mismatches& mismatches) const
    {
        double largest = 0.0;
        for (double e : expected)
        {
            largest = std::max(largest, std::abs(e));
        }
        for (std::size_t n = 0; n < expected.size(); ++n)
        {
            const double reference = expected[n], value = computed[n];
            const double tolerance = relativeTolerance * std::max(std::abs(reference), floorFraction * largest);
            if (!(std::abs(value - reference) <= tolerance))
            {
                mismatches.add(context + ", " + where[n] + ", " + name + (component[n].empty() ? "" : " ")
                               + component[n] + ": " + format(value)
                               + " against the reference's " + format(reference) + " (difference "
                               + format(value - reference) + ", tolerance " + format(tolerance) + ")");
            }
        }
    }
};

void addVec3(Quantity& q, const std::string& where, const Vec3& value, const Vec3& reference)
{
    for (int c = 0; c < 3; ++c)
    {
        q.add(where, std::string(1, "xyz"[c]), value[c], reference[c]);
    }
}

std::string bondName(const BondRecord& b)
{
    return "bond " + std::to_string(b.tagA) + "-" + std::to_string(b.tagB) + " (" + toString(b.family) + ")";
}

void compareSnapshots(const std::string& context, const Snapshot& got, const Snapshot& want, Mismatches& mismatches)
{
    if (got.particles.size() != want.particles.size() || got.bonds.size() != want.bonds.size())
    {
        mismatches.add(context + ": the scene has other particles or bonds than the reference");
        return;
    }
    Quantity force{"force"}, torque{"torque"}, centre{"centre"}, shear{"shear displacement"},
        twist{"twist angle"}, bending{"bending angle"};
    for (std::size_t i = 0; i < want.particles.size(); ++i)
    {
        const std::string where = "particle " + std::to_string(want.particles[i].tag);
        addVec3(force, where, got.particles[i].force, want.particles[i].force);
        addVec3(torque, where, got.particles[i].torque, want.particles[i].torque);
    }
    for (std::size_t k = 0; k < want.bonds.size(); ++k)
    {
        const BondRecord& g = got.bonds[k];
        const BondRecord& w = want.bonds[k];
        const std::string where = bondName(w);
        if (g.tagA != w.tagA || g.tagB != w.tagB || g.broke != w.broke || g.brokeAtStep != w.brokeAtStep)
        {
            mismatches.add(context + ", " + bondName(g) + ": broke " + toString(g.broke) + " at step "
                           + std::to_string(g.brokeAtStep) + " against the reference's " + toString(w.broke)
                           + " at step " + std::to_string(w.brokeAtStep) + " (" + where + ")");
        }
        addVec3(centre, where, g.centre, w.centre);
        addVec3(shear, where, g.shearDisplacement, w.shearDisplacement);
        twist.add(where, "", g.twistAngle, w.twistAngle);
        addVec3(bending, where, g.bendingAngle, w.bendingAngle);
    }
    for (const Quantity* q : {&force, &torque, &centre, &shear, &twist, &bending})
    {
        q->compare(context, mismatches);
    }
}

void expectMatchesReference(const Reference& computed, const std::string& how)
{
    const Reference reference = read(referencePath);
    Mismatches mismatches(how);
    for (const auto& [damping, want] : reference)
    {
        const auto got = computed.find(damping);
        if (got == computed.end() || got->second.size() != want.size())
        {
            mismatches.add("damping " + damping + ": not computed, or other steps");
            continue;
        }
        for (std::size_t n = 0; n < want.size(); ++n)
        {
            compareSnapshots("damping " + damping + ", step " + std::to_string(want[n].step), got->second[n], want[n], mismatches);
        }
    }
    EXPECT_EQ(reference.size(), computed.size()) << "damping models in " << referencePath;
}

bool regenerating()
{
    const char* flag = std::getenv("ICEDEM_REGENERATE_REFERENCE");
    return flag && std::string(flag) == "1";
}

} // namespace


// First, so that a regeneration is what the other tests then read.
TEST(BondKernelReference, RegenerateWhenAsked)
{
    if (!regenerating())
    {
        GTEST_SKIP() << "set ICEDEM_REGENERATE_REFERENCE=1 to rewrite " << referencePath;
    }
    write(computeWithKernel(bondKernelGeneric), referencePath);
    std::cout << "rewrote " << referencePath << "\n";
}

TEST(BondKernelReference, GenericKernelReproducesTheReference)
{
    expectMatchesReference(computeWithKernel(bondKernelGeneric), "generic (SSE2) batch kernel");
}

TEST(BondKernelReference, Avx2KernelReproducesTheReference)
{
    if (!__builtin_cpu_supports("avx2"))
    {
        GTEST_SKIP() << "this processor has no AVX2";
    }
    expectMatchesReference(computeWithKernel(bondKernelAvx2), "AVX2 batch kernel");
}

TEST(BondKernelReference, RunTimeChoiceReproducesTheReference)
{
    expectMatchesReference(computeWithKernel(bestBondKernel()), "bestBondKernel()");
}

TEST(BondKernelReference, SingleBondModelReproducesTheReference)
{
    expectMatchesReference(computeWithBondModel(), "BondModel::evaluate bond by bond");
}

//- The scene must keep exercising every part of the law (if a change of it
//  makes the scene lose a break, adjust the scene, not this test).
TEST(BondKernelReference, SceneExercisesEveryBreakModeAndBothFamilies)
{
    const std::size_t bonds = std::size(bondRows);
    EXPECT_GT(bonds, 2u * bondKernelLanes);
    EXPECT_NE(bonds % bondKernelLanes, 0u) << "the last batch must be padded";
    for (const auto& [damping, snapshots] : computeWithKernel(bondKernelGeneric))
    {
        std::map<std::pair<BondFamily, BreakMode>, int> count;   // at the last step
        for (const BondRecord& b : snapshots.back().bonds)
        {
            ++count[{b.family, b.broke}];
            EXPECT_NE(b.brokeAtStep, 0) << damping << " " << bondName(b) << " broke in the set-up";
        }
        int brokenFreezeBonds = 0;
        for (BreakMode mode : {BreakMode::tension, BreakMode::shear, BreakMode::twist, BreakMode::bending})
        {
            EXPECT_GT((count[{BondFamily::ice, mode}]), 0) << damping << ": no ice bond broke in " << toString(mode);
            brokenFreezeBonds += count[{BondFamily::freeze, mode}];
        }
        EXPECT_GT(brokenFreezeBonds, 0) << damping << ": no freeze-bond broke (combined criterion)";
        EXPECT_GT((count[{BondFamily::ice, BreakMode::none}]), 0) << damping << ": every ice bond broke";
        EXPECT_GT((count[{BondFamily::freeze, BreakMode::none}]), 0) << damping << ": every freeze-bond broke";
    }
}
