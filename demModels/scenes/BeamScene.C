#include "BeamScene.H"
#include "Format.H"

#include "Checkpoint.H"
#include "CommandLine.H"

#include "AtomicFile.H"
#include "Dictionary.H"
#include "ForceCurveAnalysis.H"
#include "IceBondForces.H"
#include "InputError.H"
#include "Json.H"
#include "LiggghtsInstance.H"
#include "ParticleGather.H"
#include "RandomPacking.H"
#include "SceneSetup.H"
#include "StlWriter.H"
#include "TimeStep.H"

#include "atom.h"
#include "group.h"
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



} // namespace


BeamSceneOptions BeamSceneOptions::fromArguments(int argc, char** argv)
{
    BeamSceneOptions o;
    CommandLine("iceBeamDEM")
        .text("-case", "DIR", "the case directory (default .)", o.caseDir)
        .count("-particles", "N", "particles in the beam instead of packing.particles", 20, o.particles)
        .positive("-platenSpeed", "M_PER_S", "platen speed instead of platen.speed", o.platenSpeed)
        .count("-steps", "N", "run exactly this many loading steps (benchmarks)", 1, o.steps)
        .flag("-resume", "continue from the last checkpoint in DEM/checkpoint", o.resume)
        .parse(argc, argv);
    return o;
}


BeamSceneSettings BeamSceneSettings::read(const std::string& caseDir, const BeamSceneOptions& options)
{
    BeamSceneSettings s;
    const Dictionary props = Dictionary::readFile(caseDir + "/constant/beamProperties");
    props.checkKeys({"beam", "packing", "platen", "fieldReference", "inertiaScaling"});

    auto positive = [](const Dictionary& d, const std::string& key, double def, bool required)
    {
        const double v = required ? d.getScalar(key) : d.getScalarOrDefault(key, def);
        if (!(v > 0.0))
        {
            d.fail(key, formatNumber(v) + " is not allowed; expected a positive number");
        }
        return v;
    };

    const Dictionary& beam = props.subDict("beam");
    beam.checkKeys({"length", "width", "thickness", "padLength", "endSupport", "floatingCoeffs"});
    s.length = positive(beam, "length", 0, true);
    s.width = positive(beam, "width", 0, true);
    s.thickness = positive(beam, "thickness", 0, true);
    s.padLength = positive(beam, "padLength", 0, true);
    if (2.0 * s.padLength >= s.length)
    {
        beam.fail("padLength", "the two end pads (" + formatNumber(2 * s.padLength)
                  + " m) leave no free span in a beam " + formatNumber(s.length) + " m long");
    }
    // Every condition applies: floating is the field beam's ice sheet around
    // it (a horizontal spring; no water is modelled, nothing loads the beam
    // vertically).
    s.endSupport = EndSupport::New(beam);

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
    const RandomPackingChoice choice = RandomPackingChoice::read(packing);
    s.radiusSpread = choice.radiusSpread;
    s.solidFraction = choice.solidFraction;
    s.seed = choice.seed;

    const Dictionary& platen = props.subDict("platen");
    platen.checkKeys({"diameter", "speed", "initialGap"});
    s.platenDiameter = positive(platen, "diameter", 0, true);
    s.platenSpeed = options.platenSpeed > 0.0 ? options.platenSpeed : positive(platen, "speed", 0, true);
    s.initialGap = platen.getScalarOrDefault("initialGap", 0.002);
    if (s.initialGap < 0.0)
    {
        platen.fail("initialGap", "must not be negative");
    }

    if (props.isDict("fieldReference"))
    {
        const Dictionary& field = props.subDict("fieldReference");
        field.checkKeys({"elasticSlope", "peakForce", "halfLoadTravelAfterPeak"});
        s.hasFieldReference = true;
        s.fieldSlope = positive(field, "elasticSlope", 0, true);
        s.fieldPeak = positive(field, "peakForce", 0, true);
        s.fieldHalfLoadTravel = positive(field, "halfLoadTravelAfterPeak", 0, true);
    }

    s.loading = PlatenLoadingControl::forBeamTest(caseDir, props, s.platenSpeed, s.initialGap, options.steps);
    return s;
}


BeamScene::BeamScene(MPI_Comm comm, const BeamSceneOptions& options)
:
    context_(comm, options.caseDir, "iceBeamDEM"),
    options_(options)
{
    ice_ = IceProperties::read(context_.path("constant/iceProperties"));
    settings_ = BeamSceneSettings::read(options_.caseDir, options_);
}


BeamScene::~BeamScene() = default;




void BeamScene::buildParticles()
{
    RandomPackingSpec spec;
    spec.lo = Vec3::Zero();
    spec.hi = Vec3(settings_.length, settings_.width, settings_.thickness);
    spec.particleCount = settings_.particles;
    spec.radiusSpread = settings_.radiusSpread;
    spec.targetSolidFraction = settings_.solidFraction;
    spec.seed = settings_.seed;
    body_ = buildBondedBody
    (
        spec, ice_, context_.path("constant/iceProperties"),
        [&](std::vector<ParticleSpec>& particles)
        {
            markFixedEnds(particles, 0, settings_.padLength, spec.lo, spec.hi);
        },
        [this](const std::string& line) { context_.log(line); },
        settings_.loading.inertiaScaling
    );
    describeEnds();
}


void BeamScene::describeEnds()
{
    // The platen pushes the beam along +y at mid-span; the pads (marked fixed
    // by the packing) hold the ends, their inner faces the span's ends.
    ends_.loadAxis = 1;
    ends_.pushSign = 1;
    ends_.supportX[0] = settings_.padLength;
    ends_.supportX[1] = settings_.length - settings_.padLength;
    ends_.rollerDiameter = settings_.platenDiameter;    // a steel cylinder as the platen
    ends_.contactStiffness = body_.contact.normalStiffness;
    ends_.contactDamping = body_.contact.normalDamping;
    ends_.bodyLo = Vec3::Zero();
    ends_.bodyHi = Vec3(settings_.length, settings_.width, settings_.thickness);
    ends_.density = ice_.material.density;
    ends_.particles = body_.particles;
    ends_.endOfTag.assign(body_.particles.size(), -1);
    for (std::size_t k = 0; k < body_.particles.size(); ++k)
    {
        const ParticleSpec& p = body_.particles[k];
        if (p.fixed)
        {
            ends_.endOfTag[k] = p.position.x() < 0.5 * settings_.length ? 0 : 1;
        }
    }
}


void BeamScene::writeLiggghtsInputs() const
{
    if (context_.rank() != 0)
    {
        return;
    }
    // Room for broken pieces: a particle that leaves the box is lost, which
    // the run reports as an error.
    const double margin = 0.5 * settings_.length;
    writeLiggghtsData
    (
        context_.path("DEM/packing.data"),
        "level-ice beam packing written by iceBeamDEM",
        body_.particles,
        ice_.material.density,
        Vec3(-margin, -settings_.initialGap - settings_.platenDiameter - margin, -margin),
        Vec3(settings_.length + margin, settings_.width + settings_.loading.maxTravel + margin, settings_.thickness + margin),
        2,
        [this](const ParticleSpec& p) { return p.fixed && !settings_.endSupport->padsIntegrated() ? fixedType : mobileType; }
    );
    const double radius = 0.5 * settings_.platenDiameter;
    writeCylinderStl
    (
        context_.path("DEM/platen.stl"),
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

    const double maxRadius = body_.maxRadius();
    const double skin = 0.2 * maxRadius;

    const std::string readParticles = resume
        ? "read_restart " + loading_->restartFile(*resume)
        : "read_data " + context_.path("DEM/packing.data");
    ScriptVariables variables
    {
        {"readParticles", "\"" + readParticles + "\""},
        {"platenStl", context_.path("DEM/platen.stl")},
        {"ghostCutoff", exactNumber(bondGhostCutoff(ice_, maxRadius, skin))},
        {"neighbourSkin", exactNumber(skin)},
        {"dt", exactNumber(body_.dt)},
        {"platenSpeed", exactNumber(settings_.platenSpeed)}
    };
    const ScriptVariables contactVars = contactVariables(body_.contact);
    variables.insert(variables.end(), contactVars.begin(), contactVars.end());
    lmp_ = context_.startLiggghts(variables, "DEM/in.levelIceBeam");
    LiggghtsInstance& lmp = *lmp_;

    EndSupport& support = *settings_.endSupport;
    support.defineForces(lmp, context_, ends_);
    forces_ = attachIceBonds(lmp, ice_, body_, *loading_, resume, [&] { support.defineMotion(lmp, ends_); });
    context_.log("End support " + support.description());
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
        settings_.width + settings_.loading.maxTravel + clearance,
        settings_.thickness + clearance
    );
    return stopParticlesOutside(*lmp_, lo, hi, fixedType);
}


Provenance BeamScene::inputs() const
{
    Provenance p;
    p.add("application", "iceBeamDEM");
    p.addDictionaryFile("constant/iceProperties", context_.path("constant/iceProperties"));
    p.addDictionaryFile("constant/beamProperties", context_.path("constant/beamProperties"), {"fieldReference"});
    p.addDictionaryFile("system/controlDict", context_.path("system/controlDict"), {"writeInterval", "checkpointInterval", "vtkFormat"});
    p.addFileContent("DEM/in.levelIceBeam", context_.path("DEM/in.levelIceBeam"));
    p.add("command line -particles", options_.particles > 0 ? std::to_string(options_.particles) : "not given");
    p.add("command line -platenSpeed", options_.platenSpeed > 0.0 ? shortestNumber(options_.platenSpeed) : "not given");
    return p;
}


void BeamScene::run()
{
    context_.log("iceBeamDEM: side-loaded level-ice beam, case " + options_.caseDir + ", "
        + std::to_string(context_.ranks()) + " rank(s)");
    buildParticles();
    loading_ = std::make_unique<PlatenLoading>
    (
        context_, settings_.loading, body_.dt,
        static_cast<long>(body_.particles.size()), fixedType, std::vector<std::string>{"supportReaction"}
    );
    loading_->setInputs(inputs());
    std::unique_ptr<Checkpoint> resume;
    if (options_.resume)
    {
        resume = std::make_unique<Checkpoint>(loading_->readCheckpoint());
    }
    writeLiggghtsInputs();
    MPI_Barrier(context_.comm());
    startLiggghts(resume.get());

    PlatenLoading::Hooks hooks;
    hooks.force = [this] { return platenForce(); };
    hooks.stopEjecta = [this] { return freezeEjecta(); };
    hooks.failure = [this] { return forces_.failure(); };
    hooks.extras = [this] { return std::vector<double>{settings_.endSupport->reaction(context_.comm())}; };
    loading_->run(*lmp_, *forces_.bonds, hooks, [this] { writeSummary(); });
    loading_->logEnd();
}


void BeamScene::writeSummary() const
{
    const CsvWriter& forceCurve = loading_->curve();
    const BreakageRecord& breaks = loading_->breakage();
    const LoadingState& state = loading_->state();
    const long steps = state.steps;
    if (context_.rank() != 0)
    {
        return;
    }
    std::vector<double> travel, force;
    for (std::size_t k = 0; k < forceCurve.nRows(); ++k)
    {
        travel.push_back(forceCurve.row(k)[1]);
        force.push_back(forceCurve.row(k)[2]);
    }
    double peak = 0.0;
    for (double f : force) peak = std::max(peak, f);
    if (!(peak > 0.0))
    {
        throw RunError
        (
            "the platen never touched the beam in " + std::to_string(loading_->loopSteps())
          + " loading steps (travel " + std::to_string(travel.empty() ? 0.0 : travel.back())
          + " m): no force curve to analyse and no summary.json; run more steps (-steps) or reduce"
            " platen.initialGap"
        );
    }
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
    for (const BreakEvent& e : breaks.events())
    {
        const int bin = std::clamp(static_cast<int>(e.position.x() / settings_.length * bins), 0, bins - 1);
        ++alongSpan[bin];
        if (std::abs(e.position.x() - 0.5 * settings_.length) < 0.1 * settings_.length)
        {
            centreBreaks += 1.0;
        }
    }

    auto orNull = [](bool known, double v) { return known ? Json(v) : Json(nullptr); };
    Json j;
    j["case"] = "levelIceBeam";
    j["complete"] = true;
    j["elastic_slope_N_per_m"] = rise.elasticSlope;
    j["elastic_slope_fit_R2"] = rise.slopeFitR2;
    j["first_peak_force_N"] = first.force;
    j["travel_at_first_peak_m"] = first.travel;
    j["peak_force_N"] = r.peakForce;
    j["travel_at_peak_m"] = r.travelAtPeak;
    j["half_load_reached"] = r.halfLoadReached;
    j["half_load_travel_after_peak_m"] = orNull(r.halfLoadReached, r.halfLoadTravelAfterPeak);
    j["contact_onset_travel_m"] = onset;
    if (settings_.hasFieldReference)
    {
        j["field"] =
        {
            {"elastic_slope_N_per_m", settings_.fieldSlope},
            {"peak_force_N", settings_.fieldPeak},
            {"half_load_travel_after_peak_m", settings_.fieldHalfLoadTravel}
        };
        j["slope_error"] = rise.elasticSlope / settings_.fieldSlope - 1.0;
        j["first_peak_error"] = first.force / settings_.fieldPeak - 1.0;
        j["peak_error"] = r.peakForce / settings_.fieldPeak - 1.0;
    }
    j["kinetic_to_elastic_energy_at_peak"] = state.kineticToElasticAtPeak;
    loading_->addQuasiStaticFigures(j);
    j["crack_pattern"] =
    {
        {"broken_bonds", breaks.size()},
        {"by_mode",
        {
            {"tension", breaks.count(BreakMode::tension)},
            {"shear", breaks.count(BreakMode::shear)},
            {"twist", breaks.count(BreakMode::twist)},
            {"bending", breaks.count(BreakMode::bending)}
        }},
        {"share_within_10pct_of_span_from_centre", breaks.empty() ? 0.0 : centreBreaks / breaks.size()},
        {"along_span_histogram", alongSpan}
    };
    j["end_support"] = settings_.endSupport->summary();
    std::size_t peakRow = 0;
    for (std::size_t k = 0; k < forceCurve.nRows(); ++k)
    {
        if (forceCurve.row(k)[2] > forceCurve.row(peakRow)[2]) peakRow = k;
    }
    j["support_reaction_at_peak_N"] = forceCurve.nRows() > 0 ? forceCurve.row(peakRow)[6] : 0.0;
    j["platen_speed_m_per_s"] = settings_.platenSpeed;
    j["particles"] = body_.particles.size();
    j["ejected_particles_stopped"] = state.frozenEjecta;
    j["bonds"] = body_.bondStats.totalBonds;
    j["bonds_per_particle"] = body_.bondStats.meanBondsPerParticle;
    j["solid_fraction"] = body_.packing.solidFraction;
    j["solid_fraction_target"] = settings_.solidFraction;
    j["steps"] = steps;
    j["dt"] = body_.dt;
    j["ranks"] = context_.ranks();
    j["inputs_fingerprint"] = loading_->inputs().fingerprint();
    loading_->addRunCostFigures(j);
    j["frames"] = state.frame;
    j["frames_wall_s"] = loading_->frameSeconds();
    writeFileAtomically(context_.path("postProcessing/summary.json"), jsonText(j));

    // The curve again, with displacement measured from first contact.
    CsvWriter curve({"time", "travel", "displacement", "force", "brokenBonds", "kineticEnergy", "bondEnergy",
                     "supportReaction"});
    for (std::size_t k = 0; k < forceCurve.nRows(); ++k)
    {
        const std::vector<double>& row = forceCurve.row(k);
        curve.addRow({row[0], row[1], row[1] - onset, row[2], row[3], row[4], row[5], row[6]});
    }
    curve.write(context_.path("postProcessing/platenForce.csv"));
}

} // namespace iceDEM
