#include "FloatingBlockScene.H"
#include "Format.H"

#include "AtomicFile.H"
#include "Dictionary.H"
#include "InertiaScaling.H"
#include "IceBondForces.H"
#include "Json.H"
#include "InputError.H"
#include "LiggghtsInstance.H"
#include "ParticleGather.H"
#include "TimeStep.H"
#include "WaterForces.H"

#include "atom.h"
#include "lammps.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <sstream>

namespace iceDEM
{

namespace
{

constexpr int iceType = 1;



double sphereVolume(double r)
{
    return 4.0 / 3.0 * M_PI * r * r * r;
}

} // namespace


FloatingBlockSettings FloatingBlockSettings::read(const std::string& caseDir)
{
    FloatingBlockSettings s;
    auto positive = [](const Dictionary& d, const std::string& key)
    {
        const double v = d.getScalar(key);
        if (!(v > 0.0))
        {
            d.fail(key, formatNumber(v) + " is not allowed; expected a positive number");
        }
        return v;
    };

    const Dictionary props = Dictionary::readFile(caseDir + "/constant/blockProperties");
    props.checkKeys({"block", "inertiaScaling"});
    refuseInertiaScaling(props, "inertiaScaling",
        "the floating block's answer is its motion (the heave and its period, sqrt(s) times longer with the inertia "
        "scaled, and the time it takes to come to rest), not a quasi-static load");
    const Dictionary& block = props.subDict("block");
    block.checkKeys({"lattice", "particleRadius", "spheres", "releaseDepth"});
    s.lattice = blockLatticeNames.get(block, "lattice");
    s.particleRadius = positive(block, "particleRadius");
    const std::vector<double> n = block.getScalarList("spheres");
    if (n.size() != 3 || std::any_of(n.begin(), n.end(), [](double k) { return k < 1 || k != std::floor(k) || k > 1000; }))
    {
        block.fail("spheres", "expected three whole numbers in [1, 1000]: (per row, rows, layers)");
    }
    for (int k = 0; k < 3; ++k) s.spheres[k] = static_cast<int>(n[k]);
    if (s.spheres[0] * s.spheres[1] * s.spheres[2] < 2)
    {
        block.fail("spheres", "a block needs at least two spheres");
    }
    s.releaseDepth = block.getScalar("releaseDepth");

    const Dictionary control = Dictionary::readFile(caseDir + "/system/controlDict");
    control.checkKeys
    ({
        "application", "endTime", "sampleInterval", "writeInterval", "restKineticEnergy", "restDuration",
        "vtkFormat"
    });
    s.endTime = positive(control, "endTime");
    s.sampleInterval = positive(control, "sampleInterval");
    s.writeInterval = positive(control, "writeInterval");
    s.vtkFormat = readVtkFormat(control);
    s.restKineticEnergy = positive(control, "restKineticEnergy");
    s.restDuration = positive(control, "restDuration");
    if (s.sampleInterval > s.writeInterval)
    {
        control.fail("sampleInterval", "must not exceed writeInterval");
    }
    return s;
}


std::vector<ParticleSpec> latticeBlock(BlockLattice lattice, double radius, const std::array<int, 3>& spheres)
{
    // Hexagonal: ABAB stacking, a B layer over the centres of the A layer's triangles.
    const bool hexagonal = lattice == BlockLattice::hexagonal;
    const double rowSpacing = hexagonal ? std::sqrt(3.0) * radius : 2.0 * radius;
    const double layerSpacing = hexagonal ? std::sqrt(8.0 / 3.0) * radius : 2.0 * radius;
    std::vector<ParticleSpec> particles;
    for (int k = 0; k < spheres[2]; ++k)
    {
        const bool layerB = hexagonal && k % 2 == 1;
        for (int j = 0; j < spheres[1]; ++j)
        {
            for (int i = 0; i < spheres[0]; ++i)
            {
                ParticleSpec p;
                p.position = Vec3
                (
                    2.0 * radius * i + (hexagonal ? radius * (j % 2) : 0.0) + (layerB ? radius : 0.0),
                    rowSpacing * j + (layerB ? radius / std::sqrt(3.0) : 0.0),
                    radius + layerSpacing * k
                );
                p.radius = radius;
                p.block = 0;
                particles.push_back(p);
            }
        }
    }
    return particles;
}


FloatingBlockScene::FloatingBlockScene(MPI_Comm comm, const std::string& caseDir)
:
    context_(comm, caseDir, "floatingBlockDEM"),
    curve_({"time", "draft", "draftOverHeight", "submergedVolumeFraction", "centreX", "centreY", "centreZ", "kineticEnergy"})
{
    ice_ = IceProperties::read(context_.path("constant/iceProperties"));
    water_ = WaterProperties::readCase(context_.caseDir());
    if (water_.level != WaterLevel::hydrostatic)
    {
        throw InputError(context_.path("constant/couplingProperties"), "waterLevel",
            "floatingBlockDEM needs 'hydrostatic' (got '" + toString(water_.level) + "')");
    }
    if (!(ice_.material.density < water_.hydrostatic.density))
    {
        throw InputError(context_.path("constant/iceProperties"), "material.density",
            "the ice (" + formatNumber(ice_.material.density) + " kg/m3) must be lighter than the water ("
            + formatNumber(water_.hydrostatic.density) + " kg/m3) to float");
    }
    settings_ = FloatingBlockSettings::read(context_.caseDir());
}


FloatingBlockScene::~FloatingBlockScene() = default;




void FloatingBlockScene::buildParticles()
{
    particles_ = latticeBlock(settings_.lattice, settings_.particleRadius, settings_.spheres);
    // Centred in plan on the origin, lowest point releaseDepth below the surface.
    Vec3 lo = particles_.front().position, hi = lo;
    for (const ParticleSpec& p : particles_)
    {
        lo = lo.cwiseMin(p.position);
        hi = hi.cwiseMax(p.position);
    }
    const Vec3 shift
    (
        -0.5 * (lo.x() + hi.x()),
        -0.5 * (lo.y() + hi.y()),
        water_.hydrostatic.surfaceLevel - settings_.releaseDepth
    );
    for (ParticleSpec& p : particles_)
    {
        p.position += shift;
        totalVolume_ += sphereVolume(p.radius);
    }
    totalMass_ = ice_.material.density * totalVolume_;
    blockHeight_ = hi.z() - lo.z() + 2.0 * settings_.particleRadius;

    BondBuilder builder(ice_);
    bondPairs_ = builder.build(particles_);
    bondStats_ = builder.statistics();
    contactStiffness_ = M_PI * ice_.material.youngsModulus * 2.0 * settings_.particleRadius / 4.0;
    const TimeStepLimits limits = timeStepLimits(ice_, settings_.particleRadius, bondStats_.maxBondsPerParticle);
    dt_ = chooseTimeStep(ice_, limits, context_.path("constant/iceProperties"));

    std::ostringstream msg;
    msg << "Block: " << particles_.size() << " spheres of radius " << settings_.particleRadius
        << " m on a " << (settings_.lattice == BlockLattice::cubic ? "simple cubic" : "hexagonal close-packed") << " lattice, " << hi.x() - lo.x() + 2 * settings_.particleRadius << " x "
        << hi.y() - lo.y() + 2 * settings_.particleRadius << " x " << blockHeight_ << " m\nBonds: "
        << bondStats_.summary() << "\nTime step " << dt_ << " s (limit " << limits.limit << " s)";
    context_.log(msg.str());
}


void FloatingBlockScene::startLiggghts()
{
    const double r = settings_.particleRadius;
    const double zw = water_.hydrostatic.surfaceLevel;
    const double margin = std::max(blockHeight_, 0.5);
    double xMax = 0.0, yMax = 0.0;
    for (const ParticleSpec& p : particles_)
    {
        xMax = std::max(xMax, std::abs(p.position.x()) + r);
        yMax = std::max(yMax, std::abs(p.position.y()) + r);
    }
    if (context_.rank() == 0)
    {
        writeStreamAtomically(context_.path("DEM/packing.data"), [&](std::ostream& out)
        {
            const double zLo = std::min(zw, particles_.front().position.z()) - 2.0 * blockHeight_ - margin;
            const double zHi = std::max(zw, particles_.front().position.z()) + 2.0 * blockHeight_ + margin;
            out << "LIGGGHTS data file: floating block written by floatingBlockDEM\n\n"
                << particles_.size() << " atoms\n1 atom types\n\n" << std::setprecision(17)
                << -xMax - margin << " " << xMax + margin << " xlo xhi\n"
                << -yMax - margin << " " << yMax + margin << " ylo yhi\n"
                << zLo << " " << zHi << " zlo zhi\n\nAtoms\n\n";
            for (std::size_t k = 0; k < particles_.size(); ++k)
            {
                const ParticleSpec& p = particles_[k];
                out << k + 1 << " " << iceType << " " << 2.0 * p.radius << " " << ice_.material.density << " "
                    << p.position.x() << " " << p.position.y() << " " << p.position.z() << "\n";
            }
        });
    }
    MPI_Barrier(context_.comm());

    const double maxDistFactor =
        std::max(ice_.family(BondFamily::ice).distFactor, ice_.family(BondFamily::freeze).distFactor);
    const double skin = 0.2 * r;
    const double kt = contactStiffness_ / (2.0 * (1.0 + ice_.material.poissonsRatio));
    double gn = 0.0, gt = 0.0;
    if (ice_.damping.model == DampingModel::viscous)
    {
        const double reducedMass = 0.5 * ice_.material.density * sphereVolume(r);
        gn = 2.0 * ice_.damping.dampingRatio * std::sqrt(reducedMass * contactStiffness_);
        gt = 2.0 * ice_.damping.dampingRatio * std::sqrt(reducedMass * kt);
    }
    const ScriptVariables variables
    {
        {"dataFile", context_.path("DEM/packing.data")},
        {"ghostCutoff", exactNumber(1.1 * maxDistFactor * 2.0 * r + skin)},
        {"neighbourSkin", exactNumber(skin)},
        {"kn", exactNumber(contactStiffness_)},
        {"kt", exactNumber(kt)},
        {"gn", exactNumber(gn)},
        {"gt", exactNumber(gt)},
        {"mu", exactNumber(ice_.material.frictionCoefficient)},
        {"muR", exactNumber(ice_.material.rollingFrictionCoefficient)},
        {"dt", exactNumber(dt_)},
        {"gravity", exactNumber(water_.hydrostatic.gravity)}
    };
    lmp_ = context_.startLiggghts(variables, "DEM/in.floatingBlock");
    LiggghtsInstance& lmp = *lmp_;

    // Water first, bonds (with hysteretic damping of the total) next, added mass last.
    waterForces_ = std::make_unique<WaterForces>(lmp, HydrostaticWater(water_.hydrostatic));
    waterForces_->defineForceFix();
    bonds_ = IceBondForces::define(lmp, ice_);
    waterForces_->defineAddedMassFix();
    lmp.command("run 0");   // LIGGGHTS' first set-up resets property/atom values
    bonds_->createBonds(particles_, bondPairs_);
    lmp.command("run 0");
}


FloatingBlockScene::Sample FloatingBlockScene::sample() const
{
    const LAMMPS_NS::Atom& atom = *lmp_->engine().atom;
    double lowest = HUGE_VAL, highest = -HUGE_VAL;
    double sums[4] = {0, 0, 0, 0};   // m x, m y, m z, kinetic energy
    for (int i = 0; i < atom.nlocal; ++i)
    {
        const double m = atom.rmass[i], r = atom.radius[i];
        lowest = std::min(lowest, atom.x[i][2] - r);
        highest = std::max(highest, atom.x[i][2] + r);
        for (int k = 0; k < 3; ++k)
        {
            sums[k] += m * atom.x[i][k];
            sums[3] += 0.5 * m * atom.v[i][k] * atom.v[i][k] + 0.2 * m * r * r * atom.omega[i][k] * atom.omega[i][k];
        }
    }
    double total[4];
    MPI_Allreduce(sums, total, 4, MPI_DOUBLE, MPI_SUM, context_.comm());
    double extremes[2] = {lowest, -highest}, global[2];
    MPI_Allreduce(extremes, global, 2, MPI_DOUBLE, MPI_MIN, context_.comm());
    const WaterForceTotals water = waterForces_->totals();

    Sample s;
    s.draft = water_.hydrostatic.surfaceLevel - global[0];
    s.height = -global[1] - global[0];
    s.submergedFraction = water.submergedVolume / totalVolume_;
    s.kinetic = total[3];
    s.centre = Vec3(total[0], total[1], total[2]) / totalMass_;
    return s;
}


void FloatingBlockScene::checkHealth() const
{
    std::string failure = bonds_->failure();
    if (failure.empty()) failure = waterForces_->failure();
    const long present = sumOverRanks(context_.comm(), static_cast<long>(lmp_->engine().atom->nlocal));
    if (failure.empty() && present != static_cast<long>(particles_.size()))
    {
        failure = std::to_string(particles_.size() - present) + " particle(s) left the simulation box";
    }
    int failed = failure.empty() ? 0 : 1, anyFailed = 0;
    MPI_Allreduce(&failed, &anyFailed, 1, MPI_INT, MPI_MAX, context_.comm());
    if (anyFailed)
    {
        curve_.write(context_.path("postProcessing/draft.csv"));
        throw RunError(failure.empty() ? "the run failed on another rank" : failure);
    }
}


void FloatingBlockScene::writeFrame(int frame)
{
    const GatheredState state = gatherState(*lmp_, *bonds_, -1);
    if (context_.rank() != 0)
    {
        return;
    }
    std::ostringstream name;
    name << "particles_" << std::setw(5) << std::setfill('0') << frame << ".vtp";
    writeParticlesVtp(context_.path("VTK/" + name.str()), state.particles, settings_.vtkFormat);
    if (!particlesPvd_)
    {
        particlesPvd_ = std::make_unique<PvdCollection>(context_.path("VTK/particles.pvd"));
    }
    particlesPvd_->add(lmp_->time(), name.str());
}


void FloatingBlockScene::run()
{
    context_.log("floatingBlockDEM: a bonded ice block released on still water, case " + context_.caseDir() + ", "
        + std::to_string(context_.ranks()) + " rank(s)");
    buildParticles();
    startLiggghts();
    int owned = lmp_->engine().atom->nlocal;
    atomsPerRank_.assign(context_.ranks(), 0);
    MPI_Gather(&owned, 1, MPI_INT, atomsPerRank_.data(), 1, MPI_INT, 0, context_.comm());

    const long stepsPerSample = std::max(1L, std::lround(settings_.sampleInterval / dt_));
    const long samplesPerFrame = std::max(1L, std::lround(settings_.writeInterval / settings_.sampleInterval));
    const long maxSteps = std::lround(settings_.endTime / dt_);
    const double energyScale = totalMass_ * water_.hydrostatic.gravity * blockHeight_;
    context_.log("Released with its lowest point " + formatNumber(settings_.releaseDepth) + " m below the surface; "
        + std::to_string(stepsPerSample) + " steps per sample, at most " + std::to_string(maxSteps) + " steps");

    const Sample first = sample();
    curve_.addRow({lmp_->time(), first.draft, first.draft / first.height, first.submergedFraction,
                   first.centre.x(), first.centre.y(), first.centre.z(), first.kinetic});
    int frame = 0;
    writeFrame(frame++);

    long steps = 0, sampleCount = 0, broken = 0;
    double restSince = -1.0, maxDrift = 0.0;
    Sample last = first;
    auto lastLog = std::chrono::steady_clock::now();
    while (steps < maxSteps)
    {
        const long chunk = std::min(stepsPerSample, maxSteps - steps);
        lmp_->command("run " + std::to_string(chunk) + " pre no post no");
        steps += chunk;
        ++sampleCount;
        last = sample();
        checkHealth();
        broken += sumOverRanks(context_.comm(), static_cast<long>(bonds_->takeLocalBreakEvents().size()));
        const double time = lmp_->time();
        curve_.addRow({time, last.draft, last.draft / last.height, last.submergedFraction,
                       last.centre.x(), last.centre.y(), last.centre.z(), last.kinetic});
        maxDrift = std::max(maxDrift, (last.centre - first.centre).head<2>().norm());

        if (last.kinetic < settings_.restKineticEnergy * energyScale)
        {
            if (restSince < 0.0) restSince = time;
        }
        else
        {
            restSince = -1.0;
        }
        if (sampleCount % samplesPerFrame == 0)
        {
            writeFrame(frame++);
            curve_.write(context_.path("postProcessing/draft.csv"));
        }
        const auto now = std::chrono::steady_clock::now();
        if (std::chrono::duration<double>(now - lastLog).count() > 10.0)
        {
            lastLog = now;
            std::ostringstream line;
            line << "t = " << std::fixed << std::setprecision(2) << time << " s  submerged "
                 << std::setprecision(4) << last.submergedFraction << "  draft/height " << last.draft / last.height
                 << std::scientific << std::setprecision(2) << "  kinetic " << last.kinetic / energyScale << " M g H";
            context_.log(line.str());
        }
        if (restSince >= 0.0 && time - restSince >= settings_.restDuration - 0.5 * dt_)
        {
            context_.log("At rest since t = " + formatNumber(restSince) + " s: stopping");
            break;
        }
    }
    writeFrame(frame++);
    const double wall = context_.wallSeconds();
    writeSummary(last, restSince, maxDrift, broken, wall, steps);
    std::ostringstream end;
    end << "End: " << steps << " steps, t = " << lmp_->time() << " s; submerged volume fraction "
        << std::setprecision(6) << last.submergedFraction << " (rho_i/rho_w "
        << ice_.material.density / water_.hydrostatic.density << "), draft/height " << last.draft / last.height;
    context_.log(end.str());
}


void FloatingBlockScene::writeSummary
(
    const Sample& last, double restTime, double maxDrift, long broken, double wall, long steps
) const
{
    if (context_.rank() != 0)
    {
        return;
    }
    const double ratio = ice_.material.density / water_.hydrostatic.density;
    // The same lattice, level, lowest point at 0: the draft at which it floats.
    const std::vector<ParticleSpec> level = latticeBlock(settings_.lattice, settings_.particleRadius, settings_.spheres);
    const double draftIfLevel = levelDraft(level, ratio);
    const double energyScale = totalMass_ * water_.hydrostatic.gravity * blockHeight_;

    Json j;
    j["case"] = "floatingBlock";
    j["submerged_volume_fraction"] = last.submergedFraction;
    j["density_ratio"] = ratio;
    j["submerged_volume_fraction_error"] = last.submergedFraction / ratio - 1.0;
    j["draft_m"] = last.draft;
    j["height_m"] = last.height;
    j["draft_over_height"] = last.draft / last.height;
    j["level_lattice_draft_m"] = draftIfLevel;
    j["draft_error_vs_level_lattice"] = last.draft / draftIfLevel - 1.0;
    j["max_lateral_drift_m"] = maxDrift;
    j["kinetic_energy_J"] = last.kinetic;
    j["kinetic_energy_over_MgH"] = last.kinetic / energyScale;
    j["rest_threshold_over_MgH"] = settings_.restKineticEnergy;
    j["at_rest"] = restTime >= 0.0;
    j["at_rest_since_s"] = restTime >= 0.0 ? Json(restTime) : Json(nullptr);
    j["end_time_s"] = lmp_->time();
    j["broken_bonds"] = broken;
    j["particles"] = particles_.size();
    j["bonds"] = bondStats_.totalBonds;
    j["steps"] = steps;
    j["dt"] = dt_;
    j["ranks"] = context_.ranks();
    j["atoms_per_rank_at_start"] = atomsPerRank_;
    j["wall_s"] = wall;
    writeFileAtomically(context_.path("postProcessing/summary.json"), jsonText(j));
    curve_.write(context_.path("postProcessing/draft.csv"));
}

} // namespace iceDEM
