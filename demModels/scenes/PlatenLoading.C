#include "PlatenLoading.H"
#include "BondNetworkFrame.H"
#include "Format.H"

#include "AtomicFile.H"
#include "Dictionary.H"
#include "ForceCurveAnalysis.H"
#include "InertiaScaling.H"
#include "IceBondForces.H"
#include "InputError.H"
#include "Json.H"
#include "LiggghtsInstance.H"
#include "ParticleGather.H"

#include "atom.h"
#include "lammps.h"
#include "update.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <stdexcept>

namespace iceDEM
{

namespace
{


std::vector<std::string> curveColumns(const std::vector<std::string>& extras)
{
    std::vector<std::string> columns{"time", "travel", "force", "brokenBonds", "kineticEnergy", "bondEnergy"};
    columns.insert(columns.end(), extras.begin(), extras.end());
    return columns;
}

} // namespace


void PlatenLoadingControl::readControl(const Dictionary& control)
{
    maxTravel = control.getScalar("maxTravel");
    if (!(maxTravel > 0.0))
    {
        control.fail("maxTravel", formatNumber(maxTravel) + " is not allowed; expected a positive number");
    }
    stopAfterHalfLoad = control.getBoolOrDefault("stopAfterHalfLoad", true);
    travelAfterHalfLoad = control.getScalarOrDefault("travelAfterHalfLoad", 0.005);
    if (travelAfterHalfLoad < 0.0)
    {
        control.fail("travelAfterHalfLoad", "must not be negative");
    }
    minTravel = control.getScalarOrDefault("minTravel", 0.0);
    if (minTravel < 0.0 || minTravel > maxTravel)
    {
        control.fail("minTravel", "expected 0 <= minTravel <= maxTravel");
    }
    rampTravel = control.getScalarOrDefault("rampTravel", 0.0);
    if (rampTravel < 0.0 || rampTravel > maxTravel)
    {
        control.fail("rampTravel", "expected 0 <= rampTravel <= maxTravel");
    }
    blowUpFactor = control.getScalarOrDefault("blowUpFactor", 2.0);
    if (!(blowUpFactor >= 1.0))
    {
        control.fail("blowUpFactor", "expected a number >= 1 (the kinetic energy allowed per unit of energy put in)");
    }
    maxParticleSpeed = control.getScalarOrDefault("maxParticleSpeed", 0.0);
    if (maxParticleSpeed < 0.0)
    {
        control.fail("maxParticleSpeed", "expected a speed >= 0 in m/s (0: no limit)");
    }
    maxKineticToWork = readMaxKineticToWorkRatio(control);
    sampleInterval = control.getPositiveScalarOrDefault("sampleInterval", 2e-4);
    writeInterval = control.getPositiveScalarOrDefault("writeInterval", 0.01);
    vtkFormat = readVtkFormat(control);
    checkpointInterval = control.getPositiveScalarOrDefault("checkpointInterval", 0.02);
    if (sampleInterval > writeInterval)
    {
        control.fail("sampleInterval", "must not exceed writeInterval");
    }
}


void PlatenLoadingControl::readInertiaScaling(const Dictionary& d, const std::string& key)
{
    inertiaScaling = iceDEM::readInertiaScaling(d, key);
    inertiaScalingFile = d.fileName();
    inertiaScalingEntry = d.entryPath(key);
}


PlatenLoadingControl PlatenLoadingControl::forBeamTest
(
    const std::string& caseDir,
    const Dictionary& sceneProperties,
    double speed,
    double initialGap,
    long fixedSteps
)
{
    const Dictionary control = Dictionary::readFile(caseDir + "/system/controlDict");
    control.checkKeys
    ({
        "application", "maxTravel", "stopAfterHalfLoad", "travelAfterHalfLoad",
        "sampleInterval", "writeInterval", "checkpointInterval", "maxKineticToWorkRatio", "vtkFormat"
    });
    PlatenLoadingControl loading;
    loading.readControl(control);
    loading.readInertiaScaling(sceneProperties);
    loading.speed = speed;
    loading.initialGap = initialGap;
    loading.fixedSteps = fixedSteps;
    return loading;
}


double PlatenLoadingControl::travelAt(double elapsed) const
{
    if (rampTravel <= 0.0)
    {
        return speed * elapsed;
    }
    const double tau = rampTravel / speed;
    return speed * (elapsed - tau * (1.0 - std::exp(-elapsed / tau)));
}


std::string PlatenLoadingControl::speedFormula(long startStep, double dt) const
{
    std::ostringstream f;
    f << std::setprecision(17) << speed;
    if (rampTravel > 0.0)
    {
        f << "*(1-exp(-(step-" << startStep << ")*" << dt / (rampTravel / speed) << "))";
    }
    return f.str();
}


std::string PlatenLoadingControl::travelFormula(long startStep, double dt) const
{
    std::ostringstream f;
    f << std::setprecision(17) << speed << "*((step-" << startStep << ")*" << dt;
    if (rampTravel > 0.0)
    {
        const double tau = rampTravel / speed;
        f << "-" << tau << "*(1-exp(-(step-" << startStep << ")*" << dt / tau << "))";
    }
    f << ")";
    return f.str();
}


PlatenLoading::PlatenLoading
(
    const SceneContext& context,
    const PlatenLoadingControl& control,
    double dt,
    long particleCount,
    int fixedType,
    const std::vector<std::string>& extraColumns
)
:
    context_(context),
    control_(control),
    particleCount_(particleCount),
    fixedType_(fixedType),
    wallStart_(context.startTime()),
    curve_(curveColumns(extraColumns))
{
    state_.dt = dt;
}


PlatenLoading::~PlatenLoading() = default;




double PlatenLoading::time(const LiggghtsInstance& lmp) const
{
    // Where the scene changed the step at the loading's start, LIGGGHTS' own
    // clock (atime, atimestep) is not restored to the last bit by a resume;
    // this one is the same in the uninterrupted and the resumed run.
    return stepChangedAtStart_
        ? state_.startTime + static_cast<double>(lmp.step() - state_.liggghtsStepAtStart) * state_.dt
        : lmp.time();
}


std::string PlatenLoading::restartFile(const Checkpoint& c) const
{
    return context_.path("DEM/checkpoint/liggghts.restart." + std::to_string(c.state.steps));
}


bool PlatenLoading::checkpointExists() const
{
    return std::filesystem::exists(context_.path("DEM/checkpoint/" + context_.application() + ".checkpoint"));
}


Checkpoint PlatenLoading::readCheckpoint() const
{
    const std::string file = context_.path("DEM/checkpoint/" + context_.application() + ".checkpoint");
    Checkpoint c = Checkpoint::read(file);
    requireSameInputs(Provenance::fromText(c.provenance), inputs_, file,
        "the same command without -resume (the run starts again)");
    if (c.state.dt != state_.dt)
    {
        throw InputError(context_.path("constant/iceProperties"), "timeStep",
            "the time step (" + formatNumber(state_.dt) + " s) differs from the checkpoint's ("
            + formatNumber(c.state.dt) + " s): the inputs changed since it was written");
    }
    if (c.curveColumns != curve_.columns())
    {
        throw RunError(context_.path("DEM/checkpoint") + ": the checkpoint's force curve has other columns; "
            "it was written by another version of " + context_.application() + ": delete the folder and start again");
    }
    if (!std::filesystem::exists(restartFile(c)))
    {
        throw RunError(context_.path("DEM/checkpoint") + ": the checkpoint of step " + std::to_string(c.state.steps)
            + " has no LIGGGHTS restart (" + restartFile(c) + "); delete the folder and start again");
    }
    return c;
}


void PlatenLoading::resumeFrom(const Checkpoint& c, LiggghtsInstance& lmp, IceBondForces& bonds)
{
    // LIGGGHTS restores the step number but restarts its clock at zero. Its
    // steps include any settling before the loading; the checkpoint's count
    // only the loading's.
    LAMMPS_NS::Update& update = *lmp.engine().update;
    const long expectedStep = c.state.liggghtsStepAtStart + c.state.steps;
    if (update.ntimestep != expectedStep)
    {
        throw RunError(context_.path("DEM/checkpoint") + ": LIGGGHTS' restart is at step "
            + std::to_string(update.ntimestep) + ", the application's checkpoint at step "
            + std::to_string(expectedStep) + "; delete the folder and start again");
    }
    update.atime = stepChangedAtStart_
        ? c.state.startTime + (update.ntimestep - c.state.liggghtsStepAtStart) * state_.dt
        : update.ntimestep * state_.dt;
    update.atimestep = update.ntimestep;
    bonds.restoreBonds(c.bonds);
    resumedBonds_ = c.bonds;

    state_ = c.state;
    wallBeforeResume_ = c.state.wallSeconds;
    for (const auto& row : c.curveRows) curve_.addRow(row);
    for (const BreakEvent& e : c.breaks) breakage_.append(e);
    particlesPvd_ = std::make_unique<PvdCollection>(PvdCollection::read(context_.path("VTK/particles.pvd")));
    bondsPvd_ = std::make_unique<PvdCollection>(PvdCollection::read(context_.path("VTK/bonds.pvd")));
    // Frames written after the checkpoint by the killed run are redone.
    particlesPvd_->removeAfter(time(lmp) + 0.5 * state_.dt);
    bondsPvd_->removeAfter(time(lmp) + 0.5 * state_.dt);
    resumed_ = true;
    context_.log("Resumed from the checkpoint at step " + std::to_string(state_.steps) + ", time "
        + formatNumber(time(lmp)) + " s");
}


void PlatenLoading::run
(
    LiggghtsInstance& lmp,
    IceBondForces& bonds,
    const Hooks& hooks,
    const std::function<void()>& writeSummary
)
{
    beginResultSet();
    try
    {
        load(lmp, bonds, hooks);
        checkQuasiStatic();
        writeSummary();
    }
    catch (const std::exception& e)
    {
        if (context_.rank() == 0)
        {
            // The breaks up to the last sample: what a blown-up run leaves to find its cause.
            breakage_.writeHdf5(context_.path("postProcessing/breakage.h5"));
        }
        markIncomplete(std::string("stopped by an error: ") + e.what());
        throw;
    }
}


void PlatenLoading::beginResultSet() const
{
    if (context_.rank() != 0)
    {
        return;
    }
    if (!resumed_)
    {
        namespace fs = std::filesystem;
        for (const char* file : {"postProcessing/summary.json", "postProcessing/platenForce.csv",
                                 "postProcessing/breakage.h5", "VTK/particles.pvd", "VTK/bonds.pvd"})
        {
            fs::remove(context_.path(file));
        }
        if (fs::is_directory(context_.path("VTK")))
        {
            for (const auto& entry : fs::directory_iterator(context_.path("VTK")))
            {
                const std::string name = entry.path().filename().string();
                if ((name.rfind("particles_", 0) == 0 || name.rfind("bonds_", 0) == 0)
                 && entry.path().extension() == ".vtp")
                {
                    fs::remove(entry.path());
                }
            }
        }
    }
    markIncomplete("in the making: " + context_.application() + (resumed_ ? " resumed" : " started")
        + " it and has not finished; if it was killed, `-resume` continues it");
}


void PlatenLoading::markIncomplete(const std::string& reason) const
{
    if (context_.rank() != 0)
    {
        return;
    }
    std::filesystem::create_directories(context_.path("postProcessing"));
    Json j;
    j["complete"] = false;
    j["reason"] = reason;
    j["application"] = context_.application();
    j["steps"] = state_.steps;
    writeFileAtomically(context_.path("postProcessing/summary.json"), jsonText(j));
}


void PlatenLoading::load(LiggghtsInstance& lmp, IceBondForces& bonds, const Hooks& hooks)
{
    LoadingState& st = state_;
    const double speed = control_.speed;
    const double dt = st.dt;
    const long stepsPerSample = stepsPerSampleInWholeAdvances(hooks.advance ? hooks.stepsPerAdvance : 1);
    const long samplesPerFrame = std::max(1L, std::lround(control_.writeInterval / control_.sampleInterval));
    const long samplesPerCheckpoint =
        std::max(1L, std::lround(control_.checkpointInterval / control_.sampleInterval));
    long maxSteps = control_.fixedSteps > 0
        ? control_.fixedSteps
        : std::lround((control_.maxTravel + control_.initialGap + control_.rampTravel) / (speed * dt));
    if (hooks.advance)
    {
        maxSteps = (maxSteps + stepsPerSample - 1) / stepsPerSample * stepsPerSample;
    }

    std::ostringstream plan;
    plan << "Platen at " << speed << " m/s; " << stepsPerSample << " steps per force sample, at most "
         << maxSteps << " steps (" << control_.maxTravel * 1e3 << " mm of travel after contact)";
    if (control_.inertiaScaling != 1.0)
    {
        plan << "; inertia scaled by " << control_.inertiaScaling << " (" << control_.inertiaScalingFile << ": "
             << control_.inertiaScalingEntry << "; time step " << dt << " s), refused if the kinetic energy exceeds "
             << control_.maxKineticToWork << " of the platen's work (median over the loading)";
    }
    context_.log(plan.str());

    if (resumed_)
    {
        // Each set-up the scene made since resumeFrom stepped the bonds'
        // histories once. The run that wrote the checkpoint restored them and
        // made one set-up after it (startAgainFromCheckpoint); so does this one.
        bonds.restoreBonds(resumedBonds_);
        lmp.command("run 0");
        resumedBonds_.clear();
    }
    else
    {
        st.startTime = lmp.time();   // LIGGGHTS' clock; the loading's counts from here (time())
        st.liggghtsStepAtStart = lmp.step();
        st.kineticAtStart = control_.inertiaScaling * totalKineticEnergy(lmp);
        writeFrame(lmp, bonds);
    }
    firstStep_ = st.steps;
    const auto loopStart = std::chrono::steady_clock::now();
    auto lastLog = loopStart;

    while (st.steps < maxSteps)
    {
        const long chunk = std::min(stepsPerSample, maxSteps - st.steps);
        if (hooks.advance)
        {
            hooks.advance(chunk);
        }
        else
        {
            lmp.command("run " + std::to_string(chunk) + " pre no post no");
        }
        st.steps += chunk;
        ++st.sample;
        sample(lmp, bonds, hooks);

        const double travel = control_.travelAt(time(lmp) - st.startTime);
        // Half load counts once the force stays below it; a dip that recovers
        // (noise, a crack that arrests) does not.
        if (st.previousForce >= 0.5 * st.peak)
        {
            st.halfLoadTravel = -1.0;
        }
        else if (st.halfLoadTravel < 0.0 && st.peak > 0.0)
        {
            st.halfLoadTravel = travel;
        }
        const bool done = control_.stopAfterHalfLoad && st.halfLoadTravel > 0.0
            && travel > st.halfLoadTravel + control_.travelAfterHalfLoad && travel >= control_.minTravel;

        if (st.sample % samplesPerFrame == 0)
        {
            writeFrame(lmp, bonds);
        }
        if (st.sample % samplesPerCheckpoint == 0 && !done && st.steps < maxSteps)
        {
            writeCheckpoint(lmp, bonds);
            if (!hooks.advance)
            {
                startAgainFromCheckpoint(lmp, bonds);
            }
        }

        const auto now = std::chrono::steady_clock::now();
        if (std::chrono::duration<double>(now - lastLog).count() > 10.0)
        {
            lastLog = now;
            const double elapsed = std::chrono::duration<double>(now - loopStart).count();
            const double remaining = elapsed / (st.steps - firstStep_) * (maxSteps - st.steps);
            std::ostringstream line;
            line << std::fixed << std::setprecision(1) << "t = " << time(lmp) * 1e3 << " ms"
                 << "  travel " << travel * 1e3 << " mm  force " << st.previousForce * 1e-3 << " kN"
                 << "  peak " << st.peak * 1e-3 << " kN  broken " << breakage_.size()
                 << "  " << std::setprecision(0) << (st.steps - firstStep_) * particleCount_ / elapsed
                 << " particle-steps/s  ETA <= " << formatDuration(remaining);
            context_.log(line.str());
        }

        if (done)
        {
            context_.log("Load has stayed below half the peak " + formatNumber(st.peak * 1e-3) + " kN since "
                + formatNumber((st.halfLoadTravel - st.travelAtPeak) * 1e3) + " mm after it: stopping");
            break;
        }
    }
    loopSeconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - loopStart).count();
    writeFrame(lmp, bonds);
}


long PlatenLoading::stepsPerSampleInWholeAdvances(long stepsPerAdvance) const
{
    if (stepsPerAdvance < 1)
    {
        throw std::logic_error("PlatenLoading: stepsPerAdvance must be at least 1");
    }
    const double exact = control_.sampleInterval / (control_.speed * state_.dt);
    return std::max(1L, std::lround(exact / stepsPerAdvance)) * stepsPerAdvance;
}


double PlatenLoading::wallSeconds() const
{
    return wallBeforeResume_ + std::chrono::duration<double>(std::chrono::steady_clock::now() - wallStart_).count();
}


void PlatenLoading::addRunCostFigures(Json& j) const
{
    j["wall_s"] = wallSeconds();
    j["wall_before_resume_s"] = wallBeforeResume_;
    j["loop_wall_s"] = loopSeconds_;
    j["particle_steps_per_s"] = loopSeconds_ > 0.0 ? loopSteps() * double(particleCount_) / loopSeconds_ : 0.0;
}


void PlatenLoading::logEnd() const
{
    const std::string ended = "End: " + std::to_string(state_.steps) + " steps in " + formatDuration(wallSeconds())
        + (wallBeforeResume_ > 0.0 ? " (" + formatDuration(wallBeforeResume_) + " of them before the resume)" : "")
        + ", " + std::to_string(breakage_.size()) + " bonds broken";
    if (motionPrescribed_)
    {
        // The kinetic energy is the imposed motion's: no measure of inertia's part in the force.
        context_.log(ended + " (motion prescribed: no kinetic-energy check)");
        return;
    }
    context_.log(ended + "; kinetic energy / platen work "
        + formatNumber(kineticToWorkRatio()) + " (median over the loading), kinetic / bond energy near the peak "
        + formatNumber(kineticToElasticNearPeak())
        + (control_.inertiaScaling != 1.0 ? " (inertia scaled by " + formatNumber(control_.inertiaScaling) + ")" : "")
        + (kineticToWorkRatio() > control_.maxKineticToWork
            ? "; above " + formatNumber(control_.maxKineticToWork) + ", the limit of a run with inertia scaling:"
              " not quasi-static by it"
            : std::string()));
}


std::vector<double> PlatenLoading::curveColumn(int column) const
{
    std::vector<double> values;
    for (std::size_t k = 0; k < curve_.nRows(); ++k)
    {
        values.push_back(curve_.row(k)[column]);
    }
    return values;
}


double PlatenLoading::kineticToElasticNearPeak() const
{
    return iceDEM::kineticToElasticNearPeak(curveColumn(forceColumn), curveColumn(kineticColumn),
                                            curveColumn(bondEnergyColumn));
}


double PlatenLoading::kineticToWorkRatio() const
{
    return iceDEM::kineticToWork(curveColumn(travelColumn), curveColumn(forceColumn), curveColumn(kineticColumn));
}


void PlatenLoading::addQuasiStaticFigures(Json& j) const
{
    j["inertia_scaling"] = control_.inertiaScaling;
    j["motion_prescribed"] = motionPrescribed_;
    if (motionPrescribed_)
    {
        return;   // the imposed motion's kinetic energy says nothing of inertia's part
    }
    j["kinetic_to_work_ratio"] = kineticToWorkRatio();
    j["kinetic_to_work_limit"] = control_.maxKineticToWork;
    j["kinetic_to_elastic_energy_near_peak"] = kineticToElasticNearPeak();
}


void PlatenLoading::checkQuasiStatic() const
{
    const double ratio = kineticToWorkRatio();
    if (control_.inertiaScaling == 1.0 || !(ratio > control_.maxKineticToWork))
    {
        return;
    }
    // The kinetic energy grows as s at a given platen speed.
    const double largest = control_.inertiaScaling * control_.maxKineticToWork / ratio;
    throw InputError
    (
        control_.inertiaScalingFile, control_.inertiaScalingEntry,
        formatNumber(control_.inertiaScaling) + " made the loading dynamic: its kinetic energy is "
        + formatNumber(ratio) + " of the platen's work (median over the loading), above the limit "
        + formatNumber(control_.maxKineticToWork) + " (system/controlDict maxKineticToWorkRatio); the force curve"
        " is in postProcessing/platenForce.csv. "
        + (largest >= 2.0
            ? "A factor of at most about " + formatNumber(std::floor(largest)) + " would stay below it (the ratio grows"
              " with the factor)"
            : std::string("No factor above 1 stays below it at this platen speed (the ratio grows with the factor):"
              " use 1, or a slower platen with a factor"))
    );
}


void PlatenLoading::sample(LiggghtsInstance& lmp, IceBondForces& bonds, const Hooks& hooks)
{
    LoadingState& st = state_;
    const double travel = control_.travelAt(time(lmp) - st.startTime);
    const double force = hooks.force();
    st.platenWork += 0.5 * (force + st.previousForce) * (travel - st.previousTravel);
    st.previousTravel = travel;
    st.previousForce = force;
    const double kinetic = control_.inertiaScaling * totalKineticEnergy(lmp);
    const double elastic = sumOverRanks(context_.comm(), bonds.localBondEnergy());
    for (const BreakEvent& e : gatherBreakEvents(context_.comm(), bonds.takeLocalBreakEvents()))
    {
        breakage_.append(e);
    }
    std::vector<double> row{time(lmp), travel, force, static_cast<double>(breakage_.size()), kinetic, elastic};
    if (hooks.extras)
    {
        const std::vector<double> extra = hooks.extras();
        row.insert(row.end(), extra.begin(), extra.end());
    }
    curve_.addRow(row);

    if (hooks.stopEjecta)
    {
        const long stopped = hooks.stopEjecta();
        if (stopped > 0)
        {
            st.frozenEjecta += stopped;
            context_.log(std::to_string(stopped) + " particle(s) flew clear of the body and were stopped "
                "(absorbing far field; " + std::to_string(st.frozenEjecta) + " in all)");
        }
    }
    checkHealth(lmp, bonds, hooks, kinetic);

    if (force > st.peak)
    {
        st.peak = force;
        st.travelAtPeak = travel;
        st.kineticToElasticAtPeak = elastic > 0.0 ? kinetic / elastic : 0.0;
    }
}


void PlatenLoading::checkHealth(LiggghtsInstance& lmp, IceBondForces& bonds, const Hooks& hooks, double kinetic) const
{
    // A blown-up run: NaN forces, lost bonds or particles, or kinetic energy
    // that the platen never put in.
    std::string failure = bonds.failure();
    if (failure.empty() && hooks.failure)
    {
        failure = hooks.failure();
    }
    const long present = sumOverRanks(context_.comm(), static_cast<long>(lmp.engine().atom->nlocal));
    if (failure.empty() && present != particleCount_)
    {
        failure = std::to_string(particleCount_ - present) + " particle(s) left the simulation box by time "
            + formatNumber(time(lmp)) + " s (step " + std::to_string(lmp.step()) + ")";
    }
    int failed = failure.empty() ? 0 : 1, anyFailed = 0;
    MPI_Allreduce(&failed, &anyFailed, 1, MPI_INT, MPI_MAX, context_.comm());
    if (anyFailed == 0 && !motionPrescribed_
        && kinetic > control_.blowUpFactor * (std::abs(state_.platenWork) + state_.kineticAtStart) + 1e-6)
    {
        std::ostringstream msg;
        msg << "kinetic energy " << kinetic << " J exceeds " << control_.blowUpFactor << " times the work done by the platen ("
            << state_.platenWork << " J) and the kinetic energy at the start (" << state_.kineticAtStart
            << " J) at time " << time(lmp) << " s, step " << lmp.step()
            << ": the run is unstable (lower timeStep.factor"
            << (control_.inertiaScaling != 1.0 ? " or " + control_.inertiaScalingEntry : std::string())
            << "; a body that stores energy of its own, e.g. floating"
            << " ice that falls when it breaks, may need a larger blowUpFactor in system/controlDict)";
        failure = msg.str();
        anyFailed = 1;
    }
    if (anyFailed == 0 && control_.maxParticleSpeed > 0.0)
    {
        const FastestParticle fastest = fastestParticle(lmp);
        if (fastest.speed > control_.maxParticleSpeed)
        {
            std::ostringstream msg;
            msg << "particle " << fastest.tag << " at (" << fastest.position.transpose() << ") moves at "
                << fastest.speed << " m/s, faster than maxParticleSpeed " << control_.maxParticleSpeed
                << " m/s (system/controlDict), at time " << time(lmp) << " s, step " << lmp.step()
                << ": the run has blown up";
            failure = msg.str();
            anyFailed = 1;
        }
    }
    if (anyFailed)
    {
        curve_.write(context_.path("postProcessing/platenForce.csv"));
        throw RunError(failure.empty() ? "the run blew up on another rank" : failure);
    }
}


void PlatenLoading::writeFrame(LiggghtsInstance& lmp, IceBondForces& bonds)
{
    const auto start = std::chrono::steady_clock::now();
    const GatheredState gathered = gatherState(lmp, bonds, fixedType_);
    const int frame = state_.frame++;
    if (context_.rank() != 0)
    {
        return;
    }
    BondNetworkFrame network(gathered.particles, gathered.indexOfTag);
    for (const BondLink& l : gathered.links)
    {
        network.addIntact(l.tagA, l.tagB, l.family);
    }
    for (const BreakEvent& e : breakage_.events())
    {
        network.addBroken(e);
    }

    std::ostringstream name;
    name << std::setw(5) << std::setfill('0') << frame;
    const std::string particlesFile = "particles_" + name.str() + ".vtp";
    const std::string bondsFile = "bonds_" + name.str() + ".vtp";
    writeParticlesVtp(context_.path("VTK/" + particlesFile), gathered.particles, control_.vtkFormat);
    writeBondsVtp(context_.path("VTK/" + bondsFile), network.frame(), control_.vtkFormat);
    if (!particlesPvd_)
    {
        particlesPvd_ = std::make_unique<PvdCollection>(context_.path("VTK/particles.pvd"));
        bondsPvd_ = std::make_unique<PvdCollection>(context_.path("VTK/bonds.pvd"));
    }
    particlesPvd_->add(time(lmp), particlesFile);
    bondsPvd_->add(time(lmp), bondsFile);
    breakage_.writeHdf5(context_.path("postProcessing/breakage.h5"));
    curve_.write(context_.path("postProcessing/platenForce.csv"));
    frameSeconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}


void PlatenLoading::startAgainFromCheckpoint(LiggghtsInstance& lmp, IceBondForces& bonds)
{
    // A set-up re-sorts the atoms, rebuilds the neighbour lists (contacts of
    // pairs whose bonds broke since the last build appear) and recomputes the
    // forces, stepping the bonds' histories once; the restore undoes that step.
    const std::vector<BondState> states = bonds.bondStatesOfLocalAtoms();
    lmp.command("run 0");
    bonds.restoreBonds(states);
    lmp.command("run 0");
}


void PlatenLoading::writeCheckpoint(LiggghtsInstance& lmp, IceBondForces& bonds)
{
    // LIGGGHTS' restart first (particles, contacts, platen), named by its
    // step, then ours, written atomically, which names the step. The older
    // restart is removed only after that: a run killed at any moment leaves
    // a checkpoint whose restart is there.
    const std::string dir = context_.path("DEM/checkpoint");
    if (context_.rank() == 0)
    {
        std::filesystem::create_directories(dir);
    }
    MPI_Barrier(context_.comm());
    lmp.command("write_restart " + dir + "/liggghts.restart.tmp");
    const std::vector<BondState> bondStates = gatherBondStates(context_.comm(), bonds);
    if (context_.rank() == 0)
    {
        Checkpoint c;
        c.state = state_;
        c.state.wallSeconds = wallSeconds();
        c.provenance = inputs_.text();
        c.curveColumns = curve_.columns();
        for (std::size_t k = 0; k < curve_.nRows(); ++k) c.curveRows.push_back(curve_.row(k));
        c.breaks = breakage_.events();
        c.bonds = bondStates;
        const std::string restart = restartFile(c);
        std::filesystem::rename(dir + "/liggghts.restart.tmp", restart);
        c.write(dir + "/" + context_.application() + ".checkpoint");
        for (const auto& entry : std::filesystem::directory_iterator(dir))
        {
            const std::string name = entry.path().filename().string();
            if (name.rfind("liggghts.restart", 0) == 0 && entry.path().string() != restart)
            {
                std::filesystem::remove(entry.path());
            }
        }
    }
    MPI_Barrier(context_.comm());
}

} // namespace iceDEM
