#include "BeamScene.H"

#include "Checkpoint.H"

#include "AtomicFile.H"
#include "Dictionary.H"
#include "ForceCurveAnalysis.H"
#include "IceBondForces.H"
#include "InputError.H"
#include "JsonObject.H"
#include "LiggghtsInstance.H"
#include "ParticleGather.H"
#include "RandomPacking.H"
#include "SceneSetup.H"
#include "StlWriter.H"
#include "TimeStep.H"

#include "atom.h"
#include "group.h"
#include "update.h"
#include "fix.h"
#include "lammps.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <sstream>

namespace iceDEM
{

namespace
{

constexpr int mobileType = 1;
constexpr int fixedType = 2;

std::string number(double v)
{
    std::ostringstream s;
    s << std::setprecision(10) << v;
    return s.str();
}


} // namespace


BeamSceneOptions BeamSceneOptions::fromArguments(int argc, char** argv)
{
    BeamSceneOptions o;
    const std::string usage =
        "usage: iceBeamDEM [-case DIR] [-particles N] [-platenSpeed M_PER_S] [-steps N] [-resume]";
    for (int k = 1; k < argc; ++k)
    {
        const std::string arg = argv[k];
        auto value = [&]() -> std::string
        {
            if (k + 1 >= argc)
            {
                throw InputError("command line", arg, "needs a value; " + usage);
            }
            return argv[++k];
        };
        try
        {
            if (arg == "-case") o.caseDir = value();
            else if (arg == "-particles") o.particles = std::stoi(value());
            else if (arg == "-platenSpeed") o.platenSpeed = std::stod(value());
            else if (arg == "-steps") o.steps = std::stol(value());
            else if (arg == "-resume") o.resume = true;
            else if (arg == "-help" || arg == "--help")
            {
                std::cout << usage << std::endl;
                std::exit(0);
            }
            else throw InputError("command line", arg, "unknown option; " + usage);
        }
        catch (const std::logic_error&)
        {
            throw InputError("command line", arg, "'" + std::string(argv[k]) + "' is not a number");
        }
    }
    if (o.particles < 0 || o.platenSpeed < 0.0 || o.steps < 0)
    {
        throw InputError("command line", "-particles/-platenSpeed/-steps", "must be positive");
    }
    return o;
}


BeamSceneSettings BeamSceneSettings::read(const std::string& caseDir, const BeamSceneOptions& options)
{
    BeamSceneSettings s;
    const Dictionary props = Dictionary::readFile(caseDir + "/constant/beamProperties");
    props.checkKeys({"beam", "packing", "platen"});

    auto positive = [](const Dictionary& d, const std::string& key, double def, bool required)
    {
        const double v = required ? d.getScalar(key) : d.getScalarOrDefault(key, def);
        if (!(v > 0.0))
        {
            d.fail(key, number(v) + " is not allowed; expected a positive number");
        }
        return v;
    };

    const Dictionary& beam = props.subDict("beam");
    beam.checkKeys({"length", "width", "thickness", "padLength"});
    s.length = positive(beam, "length", 0, true);
    s.width = positive(beam, "width", 0, true);
    s.thickness = positive(beam, "thickness", 0, true);
    s.padLength = positive(beam, "padLength", 0, true);
    if (2.0 * s.padLength >= s.length)
    {
        beam.fail("padLength", "the two end pads (" + number(2 * s.padLength)
                  + " m) leave no free span in a beam " + number(s.length) + " m long");
    }

    const Dictionary& packing = props.subDict("packing");
    packing.checkKeys({"particles", "radiusSpread", "solidFraction", "seed"});
    s.particles = packing.getLabel("particles");   // validated even when overridden
    if (options.particles > 0)
    {
        s.particles = options.particles;
    }
    if (s.particles < 20)
    {
        packing.fail("particles", "at least 20 particles are needed");
    }
    s.radiusSpread = packing.getScalarOrDefault("radiusSpread", 0.0);
    if (s.radiusSpread < 0.0 || s.radiusSpread >= 0.9)
    {
        packing.fail("radiusSpread", "expected a relative half-width in [0, 0.9)");
    }
    s.solidFraction = packing.getScalarOrDefault("solidFraction", 0.6);
    if (s.solidFraction <= 0.0 || s.solidFraction >= 0.74)
    {
        packing.fail("solidFraction", "expected a solid fraction in (0, 0.74)");
    }
    s.seed = static_cast<unsigned>(packing.getLabelOrDefault("seed", 1));

    const Dictionary& platen = props.subDict("platen");
    platen.checkKeys({"diameter", "speed", "initialGap"});
    s.platenDiameter = positive(platen, "diameter", 0, true);
    s.platenSpeed = options.platenSpeed > 0.0 ? options.platenSpeed : positive(platen, "speed", 0, true);
    s.initialGap = platen.getScalarOrDefault("initialGap", 0.002);
    if (s.initialGap < 0.0)
    {
        platen.fail("initialGap", "must not be negative");
    }

    const Dictionary control = Dictionary::readFile(caseDir + "/system/controlDict");
    control.checkKeys
    ({
        "application", "maxTravel", "stopAfterHalfLoad", "travelAfterHalfLoad",
        "sampleInterval", "writeInterval", "checkpointInterval"
    });
    s.maxTravel = positive(control, "maxTravel", 0, true);
    s.stopAfterHalfLoad = control.getBoolOrDefault("stopAfterHalfLoad", true);
    s.travelAfterHalfLoad = control.getScalarOrDefault("travelAfterHalfLoad", 0.005);
    s.sampleInterval = positive(control, "sampleInterval", 2e-4, false);
    s.writeInterval = positive(control, "writeInterval", 0.01, false);
    s.checkpointInterval = positive(control, "checkpointInterval", 0.02, false);
    if (s.sampleInterval > s.writeInterval)
    {
        control.fail("sampleInterval", "must not exceed writeInterval");
    }
    return s;
}


BeamScene::BeamScene(MPI_Comm comm, const BeamSceneOptions& options)
:
    comm_(comm),
    options_(options),
    curve_({"time", "travel", "force", "brokenBonds", "kineticEnergy", "bondEnergy"})
{
    MPI_Comm_rank(comm_, &rank_);
    MPI_Comm_size(comm_, &ranks_);
    ice_ = IceProperties::read(path("constant/iceProperties"));
    settings_ = BeamSceneSettings::read(options_.caseDir, options_);
}


BeamScene::~BeamScene() = default;


std::string BeamScene::path(const std::string& relative) const
{
    return options_.caseDir + "/" + relative;
}


void BeamScene::log(const std::string& line) const
{
    if (rank_ == 0)
    {
        std::cout << line << std::endl;
    }
}


void BeamScene::buildParticles()
{
    // Every rank builds the same packing (a pure function of its inputs).
    RandomPackingSpec spec;
    spec.lo = Vec3::Zero();
    spec.hi = Vec3(settings_.length, settings_.width, settings_.thickness);
    spec.particleCount = settings_.particles;
    spec.radiusSpread = settings_.radiusSpread;
    spec.targetSolidFraction = settings_.solidFraction;
    spec.seed = settings_.seed;
    RandomPackingStats stats;
    particles_ = buildRandomPacking(spec, stats);
    markFixedEnds(particles_, 0, settings_.padLength, spec.lo, spec.hi);

    std::ostringstream msg;
    msg << "Packing: " << particles_.size() << " particles, radius " << stats.minRadius << " - "
        << stats.maxRadius << " m, solid fraction " << stats.solidFraction
        << ", largest overlap " << stats.maxOverlap << " of the mean radius";
    log(msg.str());

    BondBuilder builder(ice_);
    bondPairs_ = builder.build(particles_);
    bondStats_ = builder.statistics();
    log("Bonds: " + bondStats_.summary());

    double minMass = HUGE_VAL;
    for (const ParticleSpec& p : particles_)
    {
        minMass = std::min(minMass, ice_.material.density * 4.0 / 3.0 * M_PI * std::pow(p.radius, 3));
    }
    contact_ = ContactParameters::of(ice_, 2.0 * stats.meanRadius, minMass);

    const TimeStepLimits limits = timeStepLimits(ice_, stats.minRadius, bondStats_.maxBondsPerParticle);
    dt_ = chooseTimeStep(ice_, limits, path("constant/iceProperties"));
    std::ostringstream step;
    step << "Time step " << dt_ << " s (limit " << limits.limit << " s; stiffest spring: "
         << limits.stiffestSpringName << ", critical " << limits.stiffestSpring << " s)";
    log(step.str());
}


void BeamScene::writeLiggghtsInputs() const
{
    if (rank_ != 0)
    {
        return;
    }
    // Room for broken pieces: a particle that leaves the box is lost, which
    // the run reports as an error.
    const double margin = 0.5 * settings_.length;
    writeLiggghtsData
    (
        path("DEM/packing.data"),
        "level-ice beam packing written by iceBeamDEM",
        particles_,
        ice_.material.density,
        Vec3(-margin, -settings_.initialGap - settings_.platenDiameter - margin, -margin),
        Vec3(settings_.length + margin, settings_.width + settings_.maxTravel + margin, settings_.thickness + margin),
        2,
        [](const ParticleSpec& p) { return p.fixed ? fixedType : mobileType; }
    );
    const double radius = 0.5 * settings_.platenDiameter;
    writeCylinderStl
    (
        path("DEM/platen.stl"),
        Vec3(0.5 * settings_.length, -radius - settings_.initialGap, -0.02),
        Vec3(0.0, 0.0, 1.0),
        radius,
        settings_.thickness + 0.04,
        48,
        "platen"
    );
}


void BeamScene::startLiggghts(const Checkpoint* resume)
{
    LiggghtsInstance::reportErrorsFromLog(path("log.liggghts"));
    lmp_ = std::make_unique<LiggghtsInstance>(comm_, path("log.liggghts"));
    LiggghtsInstance& lmp = *lmp_;

    double maxRadius = 0.0;
    for (const ParticleSpec& p : particles_)
    {
        maxRadius = std::max(maxRadius, p.radius);
    }
    const double skin = 0.2 * maxRadius;

    const std::string readParticles = resume
        ? "read_restart " + path("DEM/checkpoint/liggghts.restart")
        : "read_data " + path("DEM/packing.data");
    ScriptVariables variables
    {
        {"readParticles", "\"" + readParticles + "\""},
        {"platenStl", path("DEM/platen.stl")},
        {"ghostCutoff", exactNumber(bondGhostCutoff(ice_, maxRadius, skin))},
        {"neighbourSkin", exactNumber(skin)},
        {"dt", exactNumber(dt_)},
        {"platenSpeed", exactNumber(settings_.platenSpeed)}
    };
    const ScriptVariables contactVars = contactVariables(contact_);
    variables.insert(variables.end(), contactVars.begin(), contactVars.end());
    defineScriptVariables(lmp, variables, path("DEM/variables.generated"), "iceBeamDEM");

    const std::string script = path("DEM/in.levelIceBeam");
    if (!std::filesystem::exists(script))
    {
        throw InputError(script, "(file)", "the LIGGGHTS input script is missing");
    }
    lmp.runScript(script);

    bonds_ = std::make_unique<IceBondForces>(lmp, ice_, contact_.normalStiffness);
    lmp.command("fix iceBondForces all external pf/callback 1 1");
    bonds_->attach("iceBondForces");
    // LIGGGHTS' set-up of the first run resets property/atom values to their
    // defaults, so the bonds are stored after it.
    lmp.command("run 0");
    if (resume)
    {
        // LIGGGHTS restores the step number but restarts its clock at zero.
        LAMMPS_NS::Update& update = *lmp.engine().update;
        if (update.ntimestep != resume->state.steps)
        {
            throw RunError(path("DEM/checkpoint") + ": LIGGGHTS' restart is at step "
                + std::to_string(update.ntimestep) + ", the application's checkpoint at step "
                + std::to_string(resume->state.steps) + "; delete the folder and start again");
        }
        update.atime = resume->state.steps * dt_;
        update.atimestep = update.ntimestep;
        bonds_->restoreBonds(resume->bonds);
    }
    else
    {
        bonds_->createBonds(particles_, bondPairs_);
    }
    lmp.command("run 0");   // forces of the first step with the bonds in place
}


double BeamScene::platenForce() const
{
    // Force of the particles on the platen; they push it back along -y.
    return -lmp_->fix("platen").compute_vector(1);
}


long BeamScene::freezeEjecta()
{
    // Without gravity or water nothing stops a piece that breaks off: a
    // particle that has flown well clear of the beam (alone or in a bonded
    // fragment) is stopped and fixed where it is (an absorbing far field), so
    // that it never leaves the box.
    const double clearance = 0.3;
    const Vec3 lo(-clearance, -clearance - settings_.platenDiameter, -clearance);
    const Vec3 hi
    (
        settings_.length + clearance,
        settings_.width + settings_.maxTravel + clearance,
        settings_.thickness + clearance
    );
    LAMMPS_NS::LAMMPS& engine = lmp_->engine();
    LAMMPS_NS::Atom& atom = *engine.atom;
    const int mobileBit = engine.group->bitmask[engine.group->find("mobile")];
    long frozen = 0;
    for (int i = 0; i < atom.nlocal; ++i)
    {
        if (!(atom.mask[i] & mobileBit))
        {
            continue;
        }
        const Vec3 x(atom.x[i][0], atom.x[i][1], atom.x[i][2]);
        if ((x.array() < lo.array()).any() || (x.array() > hi.array()).any())
        {
            atom.mask[i] &= ~mobileBit;
            atom.type[i] = fixedType;
            for (int k = 0; k < 3; ++k)
            {
                atom.v[i][k] = atom.omega[i][k] = 0.0;
            }
            ++frozen;
        }
    }
    return sumOverRanks(comm_, frozen);
}


void BeamScene::collectBreakEvents()
{
    const std::vector<BreakEvent> all = gatherBreakEvents(comm_, bonds_->takeLocalBreakEvents());
    for (const BreakEvent& e : all)
    {
        breakage_.append(e);
    }
}


void BeamScene::writeFrame(int frame)
{
    const GatheredState state = gatherState(*lmp_, *bonds_, fixedType);
    if (rank_ != 0)
    {
        return;
    }
    BondFrame network;
    auto addLink = [&](long a, long b, int family, int stateCode, int mode, double time)
    {
        const auto ia = state.indexOfTag.find(a);
        const auto ib = state.indexOfTag.find(b);
        if (ia == state.indexOfTag.end() || ib == state.indexOfTag.end())
        {
            return;
        }
        network.endA.push_back(state.particles.position[ia->second]);
        network.endB.push_back(state.particles.position[ib->second]);
        network.family.push_back(family);
        network.state.push_back(stateCode);
        network.mode.push_back(mode);
        network.time.push_back(time);
    };
    for (const BondLink& l : state.links)
    {
        addLink(l.tagA, l.tagB, l.family, 0, 0, -1.0);
    }
    for (const BreakEvent& e : breakage_.events())
    {
        addLink(e.tagA, e.tagB, static_cast<int>(e.family), 1, static_cast<int>(e.mode), e.time);
    }

    std::ostringstream name;
    name << std::setw(5) << std::setfill('0') << frame;
    const std::string particlesFile = "particles_" + name.str() + ".vtp";
    const std::string bondsFile = "bonds_" + name.str() + ".vtp";
    writeParticlesVtp(path("VTK/" + particlesFile), state.particles);
    writeBondsVtp(path("VTK/" + bondsFile), network);
    if (!particlesPvd_)
    {
        particlesPvd_ = std::make_unique<PvdCollection>(path("VTK/particles.pvd"));
        bondsPvd_ = std::make_unique<PvdCollection>(path("VTK/bonds.pvd"));
    }
    particlesPvd_->add(lmp_->time(), particlesFile);
    bondsPvd_->add(lmp_->time(), bondsFile);
    breakage_.writeHdf5(path("postProcessing/breakage.h5"));
    curve_.write(path("postProcessing/platenForce.csv"));
}


void BeamScene::writeCheckpoint()
{
    // LIGGGHTS' restart first (particles, contacts, platen), then ours; a
    // checkpoint counts only when both are complete, and ours names the step.
    const std::string dir = path("DEM/checkpoint");
    if (rank_ == 0)
    {
        std::filesystem::create_directories(dir);
    }
    MPI_Barrier(comm_);
    lmp_->command("write_restart " + dir + "/liggghts.restart.tmp");
    const std::vector<BondState> bonds = gatherBondStates(comm_, *bonds_);
    if (rank_ == 0)
    {
        Checkpoint c;
        c.state = loading_;
        c.curveColumns = curve_.columns();
        for (std::size_t k = 0; k < curve_.nRows(); ++k) c.curveRows.push_back(curve_.row(k));
        c.breaks = breakage_.events();
        c.bonds = bonds;
        std::filesystem::rename(dir + "/liggghts.restart.tmp", dir + "/liggghts.restart");
        c.write(dir + "/iceBeamDEM.checkpoint");
    }
    MPI_Barrier(comm_);
}


void BeamScene::run()
{
    const auto wallStart = std::chrono::steady_clock::now();
    log("iceBeamDEM: side-loaded level-ice beam, case " + options_.caseDir + ", "
        + std::to_string(ranks_) + " rank(s)");
    buildParticles();

    std::unique_ptr<Checkpoint> resume;
    if (options_.resume)
    {
        resume = std::make_unique<Checkpoint>(Checkpoint::read(path("DEM/checkpoint/iceBeamDEM.checkpoint")));
        if (resume->state.dt != dt_)
        {
            throw InputError(path("constant/iceProperties"), "timeStep",
                "the time step (" + number(dt_) + " s) differs from the checkpoint's ("
                + number(resume->state.dt) + " s): the inputs changed since it was written");
        }
    }
    writeLiggghtsInputs();
    MPI_Barrier(comm_);
    startLiggghts(resume.get());

    LoadingState& st = loading_;
    st.dt = dt_;
    if (resume)
    {
        st = resume->state;
        for (const auto& row : resume->curveRows) curve_.addRow(row);
        for (const BreakEvent& e : resume->breaks) breakage_.append(e);
        particlesPvd_ = std::make_unique<PvdCollection>(PvdCollection::read(path("VTK/particles.pvd")));
        bondsPvd_ = std::make_unique<PvdCollection>(PvdCollection::read(path("VTK/bonds.pvd")));
        // Frames written after the checkpoint by the killed run are redone.
        particlesPvd_->removeAfter(lmp_->time() + 0.5 * dt_);
        bondsPvd_->removeAfter(lmp_->time() + 0.5 * dt_);
        log("Resumed from the checkpoint at step " + std::to_string(st.steps) + ", time "
            + number(lmp_->time()) + " s");
    }

    const double speed = settings_.platenSpeed;
    const long stepsPerSample =
        std::max(1L, std::lround(settings_.sampleInterval / (speed * dt_)));
    const long samplesPerFrame =
        std::max(1L, std::lround(settings_.writeInterval / settings_.sampleInterval));
    const long samplesPerCheckpoint =
        std::max(1L, std::lround(settings_.checkpointInterval / settings_.sampleInterval));
    const long maxSteps = options_.steps > 0
        ? options_.steps
        : std::lround((settings_.maxTravel + settings_.initialGap) / (speed * dt_));

    std::ostringstream plan;
    plan << "Platen at " << speed << " m/s; " << stepsPerSample << " steps per force sample, at most "
         << maxSteps << " steps (" << settings_.maxTravel * 1e3 << " mm of travel after contact)";
    log(plan.str());

    auto lastLog = std::chrono::steady_clock::now();
    if (!resume)
    {
        writeFrame(st.frame++);
    }
    const long firstStep = st.steps;
    const auto loopStart = std::chrono::steady_clock::now();

    while (st.steps < maxSteps)
    {
        const long chunk = std::min(stepsPerSample, maxSteps - st.steps);
        lmp_->command("run " + std::to_string(chunk) + " pre no post no");
        st.steps += chunk;
        ++st.sample;

        const double travel = speed * lmp_->time();
        const double force = platenForce();
        st.platenWork += 0.5 * (force + st.previousForce) * speed * chunk * dt_;
        st.previousForce = force;
        const double kinetic = totalKineticEnergy(*lmp_);
        const double elastic = sumOverRanks(comm_, bonds_->localBondEnergy());
        collectBreakEvents();
        curve_.addRow
        ({
            lmp_->time(), travel, force, static_cast<double>(breakage_.size()), kinetic, elastic
        });

        const long frozen = freezeEjecta();
        if (frozen > 0)
        {
            st.frozenEjecta += frozen;
            log(std::to_string(frozen) + " particle(s) flew clear of the beam and were stopped "
                "(absorbing far field; " + std::to_string(st.frozenEjecta) + " in all)");
        }
        checkHealth(kinetic, st.platenWork);

        if (force > st.peak)
        {
            st.peak = force;
            st.travelAtPeak = travel;
            st.kineticToElasticAtPeak = elastic > 0.0 ? kinetic / elastic : 0.0;
        }
        // Half load counts once the force stays below it; a dip that recovers
        // (noise, a crack that arrests) does not.
        if (force >= 0.5 * st.peak)
        {
            st.halfLoadTravel = -1.0;
        }
        else if (st.halfLoadTravel < 0.0 && st.peak > 0.0)
        {
            st.halfLoadTravel = travel;
        }
        const bool done = settings_.stopAfterHalfLoad && st.halfLoadTravel > 0.0
            && travel > st.halfLoadTravel + settings_.travelAfterHalfLoad;

        if (st.sample % samplesPerFrame == 0)
        {
            writeFrame(st.frame++);
        }
        if (st.sample % samplesPerCheckpoint == 0 && !done && st.steps < maxSteps)
        {
            writeCheckpoint();
        }

        const auto now = std::chrono::steady_clock::now();
        if (std::chrono::duration<double>(now - lastLog).count() > 10.0)
        {
            lastLog = now;
            const double elapsed = std::chrono::duration<double>(now - loopStart).count();
            const double remaining = elapsed / (st.steps - firstStep) * (maxSteps - st.steps);
            std::ostringstream line;
            line << std::fixed << std::setprecision(1) << "t = " << lmp_->time() * 1e3 << " ms"
                 << "  travel " << travel * 1e3 << " mm  force " << force * 1e-3 << " kN"
                 << "  peak " << st.peak * 1e-3 << " kN  broken " << breakage_.size()
                 << "  " << std::setprecision(0) << (st.steps - firstStep) * particles_.size() / elapsed
                 << " particle-steps/s  ETA <= " << formatDuration(remaining);
            log(line.str());
        }

        if (done)
        {
            log("Load has stayed below half the peak " + number(st.peak * 1e-3) + " kN since "
                + number((st.halfLoadTravel - st.travelAtPeak) * 1e3) + " mm after it: stopping");
            break;
        }
    }

    const double loop =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - loopStart).count();
    writeFrame(st.frame++);
    const double wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - wallStart).count();
    writeSummary(wall, loop, st.steps, st.steps - firstStep);
    log("End: " + std::to_string(st.steps) + " steps in " + formatDuration(wall) + ", "
        + std::to_string(breakage_.size()) + " bonds broken");
}


void BeamScene::checkHealth(double kinetic, double platenWork)
{
    // A blown-up run: NaN forces, lost bonds or particles, or kinetic energy
    // that the platen never put in.
    std::string failure = bonds_->failure();
    const long present = sumOverRanks(comm_, static_cast<long>(lmp_->engine().atom->nlocal));
    if (failure.empty() && present != static_cast<long>(particles_.size()))
    {
        failure = std::to_string(particles_.size() - present) + " particle(s) left the simulation box by time "
            + number(lmp_->time()) + " s (step " + std::to_string(lmp_->step()) + ")";
    }
    int failed = failure.empty() ? 0 : 1, anyFailed = 0;
    MPI_Allreduce(&failed, &anyFailed, 1, MPI_INT, MPI_MAX, comm_);
    if (anyFailed == 0 && kinetic > 2.0 * std::abs(platenWork) + 1e-6)
    {
        std::ostringstream msg;
        msg << "kinetic energy " << kinetic << " J exceeds twice the work done by the platen ("
            << platenWork << " J) at time " << lmp_->time() << " s, step " << lmp_->step()
            << ": the run is unstable (lower timeStep.factor)";
        failure = msg.str();
        anyFailed = 1;
    }
    if (anyFailed)
    {
        curve_.write(path("postProcessing/platenForce.csv"));
        throw RunError(failure.empty() ? "the run blew up on another rank" : failure);
    }
}


void BeamScene::writeSummary(double wallSeconds, double loopSeconds, long steps, long loopSteps) const
{
    if (rank_ != 0)
    {
        return;
    }
    std::vector<double> travel, force;
    for (std::size_t k = 0; k < curve_.nRows(); ++k)
    {
        travel.push_back(curve_.row(k)[1]);
        force.push_back(curve_.row(k)[2]);
    }
    double peak = 0.0;
    for (double f : force) peak = std::max(peak, f);
    const double onset = contactOnset(travel, force, 0.01 * peak);
    std::vector<double> displacement;
    for (double t : travel) displacement.push_back(t - onset);
    const ForceCurveResult r = analyseForceCurve(displacement, force);
    // The field's peak is the load at which the centre crack formed: the first
    // major load drop. Later the cracked beam can carry more (see README).
    // The elastic slope is fitted on the rise to that first peak.
    const FirstPeak first = firstPeak(displacement, force, 0.1);
    const std::vector<double> riseTravel(displacement.begin(), displacement.begin() + first.index + 1);
    const std::vector<double> riseForce(force.begin(), force.begin() + first.index + 1);
    const ForceCurveResult rise = analyseForceCurve(riseTravel, riseForce);

    // Crack pattern: where along the span and across the width the bonds broke.
    const int bins = 10;
    std::vector<int> alongSpan(bins, 0);
    double centreBreaks = 0.0;
    for (const BreakEvent& e : breakage_.events())
    {
        const int bin = std::clamp(static_cast<int>(e.position.x() / settings_.length * bins), 0, bins - 1);
        ++alongSpan[bin];
        if (std::abs(e.position.x() - 0.5 * settings_.length) < 0.1 * settings_.length)
        {
            centreBreaks += 1.0;
        }
    }

    const double fieldSlope = 6.25e6, fieldPeak = 120000.0;
    std::ostringstream j;
    j << std::setprecision(10) << "{\n"
      << "  \"case\": \"levelIceBeam\",\n"
      << "  \"elastic_slope_N_per_m\": " << jsonNumber(rise.elasticSlope) << ",\n"
      << "  \"elastic_slope_fit_R2\": " << jsonNumber(rise.slopeFitR2) << ",\n"
      << "  \"first_peak_force_N\": " << jsonNumber(first.force) << ",\n"
      << "  \"travel_at_first_peak_m\": " << jsonNumber(first.travel) << ",\n"
      << "  \"peak_force_N\": " << jsonNumber(r.peakForce) << ",\n"
      << "  \"travel_at_peak_m\": " << jsonNumber(r.travelAtPeak) << ",\n"
      << "  \"half_load_reached\": " << (r.halfLoadReached ? "true" : "false") << ",\n"
      << "  \"half_load_travel_after_peak_m\": "
      << (r.halfLoadReached ? jsonNumber(r.halfLoadTravelAfterPeak) : "null") << ",\n"
      << "  \"contact_onset_travel_m\": " << jsonNumber(onset) << ",\n"
      << "  \"field\": {\"elastic_slope_N_per_m\": " << fieldSlope << ", \"peak_force_N\": " << fieldPeak
      << ", \"half_load_travel_after_peak_m\": 0.07},\n"
      << "  \"slope_error\": " << jsonNumber(rise.elasticSlope / fieldSlope - 1.0) << ",\n"
      << "  \"first_peak_error\": " << jsonNumber(first.force / fieldPeak - 1.0) << ",\n"
      << "  \"peak_error\": " << jsonNumber(r.peakForce / fieldPeak - 1.0) << ",\n"
      << "  \"kinetic_to_elastic_energy_at_peak\": " << jsonNumber(loading_.kineticToElasticAtPeak) << ",\n"
      << "  \"crack_pattern\": {\n"
      << "    \"broken_bonds\": " << breakage_.size() << ",\n"
      << "    \"by_mode\": {\"tension\": " << breakage_.count(BreakMode::tension)
      << ", \"shear\": " << breakage_.count(BreakMode::shear)
      << ", \"twist\": " << breakage_.count(BreakMode::twist)
      << ", \"bending\": " << breakage_.count(BreakMode::bending) << "},\n"
      << "    \"share_within_10pct_of_span_from_centre\": "
      << jsonNumber(breakage_.empty() ? 0.0 : centreBreaks / breakage_.size()) << ",\n"
      << "    \"along_span_histogram\": [";
    for (int b = 0; b < bins; ++b) j << (b ? ", " : "") << alongSpan[b];
    j << "]\n  },\n"
      << "  \"platen_speed_m_per_s\": " << settings_.platenSpeed << ",\n"
      << "  \"particles\": " << particles_.size() << ",\n"
      << "  \"ejected_particles_stopped\": " << loading_.frozenEjecta << ",\n"
      << "  \"bonds\": " << bondStats_.totalBonds << ",\n"
      << "  \"bonds_per_particle\": " << bondStats_.meanBondsPerParticle << ",\n"
      << "  \"steps\": " << steps << ",\n"
      << "  \"dt\": " << dt_ << ",\n"
      << "  \"ranks\": " << ranks_ << ",\n"
      << "  \"wall_s\": " << wallSeconds << ",\n"
      << "  \"loop_wall_s\": " << loopSeconds << ",\n"
      << "  \"particle_steps_per_s\": " << loopSteps * particles_.size() / loopSeconds << "\n"
      << "}\n";
    writeFileAtomically(path("postProcessing/summary.json"), j.str());

    // The curve again, with displacement measured from first contact.
    CsvWriter curve({"time", "travel", "displacement", "force", "brokenBonds", "kineticEnergy", "bondEnergy"});
    for (std::size_t k = 0; k < curve_.nRows(); ++k)
    {
        const std::vector<double>& row = curve_.row(k);
        curve.addRow({row[0], row[1], row[1] - onset, row[2], row[3], row[4], row[5]});
    }
    curve.write(path("postProcessing/platenForce.csv"));
}

} // namespace iceDEM
