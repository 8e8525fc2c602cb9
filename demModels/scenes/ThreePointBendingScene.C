#include "ThreePointBendingScene.H"
#include "CommandLine.H"
#include "Format.H"

#include "AppMain.H"
#include "AtomicFile.H"
#include "BreakageRecord.H"
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

#include "atom.h"
#include "fix.h"
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

constexpr int mobileType = 1;
constexpr int fixedType = 2;
const char* const application = "threePointBendingDEM";


//- The positive entry `key` of d (InputError naming it otherwise).
double positiveEntry(const Dictionary& d, const std::string& key)
{
    const double v = d.getScalar(key);
    if (!(v > 0.0))
    {
        d.fail(key, formatNumber(v) + " is not allowed; expected a positive number");
    }
    return v;
}

//- Height of the axis of a cylinder across the beam (along y, at x = xAxis)
//  at which it just touches the beam from below (side -1) or above (+1).
double touchingAxisHeight(const std::vector<ParticleSpec>& particles, double xAxis, double radius, int side)
{
    double height = -side * HUGE_VAL;
    for (const ParticleSpec& p : particles)
    {
        const double reach = radius + p.radius;
        const double dx = p.position.x() - xAxis;
        if (std::abs(dx) < reach)
        {
            const double touching = p.position.z() + side * std::sqrt(reach * reach - dx * dx);
            height = side < 0 ? std::min(height, touching) : std::max(height, touching);
        }
    }
    return height;
}

} // namespace


ThreePointBendingOptions ThreePointBendingOptions::fromArguments(int argc, char** argv)
{
    ThreePointBendingOptions o;
    CommandLine(application)
        .text("-case", "DIR", "the case directory (default .)", o.caseDir)
        .positive("-thickness", "M", "beam thickness instead of beam.thickness", o.thickness)
        .flag("-quick", "the quick resolution (packing.quickParticleDiameter, constant/iceProperties.quick)", o.quick)
        .positive("-platenSpeed", "M_PER_S", "platen speed instead of platen.speed", o.platenSpeed)
        .count("-steps", "N", "run exactly this many loading steps", 1, o.steps)
        .flag("-resume", "continue from the last checkpoint in DEM/checkpoint", o.resume)
        .parse(argc, argv);
    return o;
}


ThreePointBendingSettings ThreePointBendingSettings::read
(
    const std::string& caseDir,
    const ThreePointBendingOptions& options
)
{
    ThreePointBendingSettings s;
    const Dictionary props = Dictionary::readFile(caseDir + "/constant/bendingProperties");
    props.checkKeys({"beam", "supports", "platen", "packing", "targetStrength", "inertiaScaling"});

    const Dictionary& beam = props.subDict("beam");
    beam.checkKeys({"length", "width", "thickness"});
    s.length = positiveEntry(beam, "length");
    s.width = positiveEntry(beam, "width");
    s.thickness = positiveEntry(beam, "thickness");     // validated even when overridden
    if (options.thickness > 0.0)
    {
        s.thickness = options.thickness;
    }

    const Dictionary& supports = props.subDict("supports");
    supports.checkKeys({"span", "diameter", "endSupport"});
    s.span = positiveEntry(supports, "span");
    s.supportDiameter = positiveEntry(supports, "diameter");
    if (s.span > s.length)
    {
        supports.fail("span", formatNumber(s.span) + " m is not allowed: the supports must lie under the beam, "
                      "whose beam.length is " + formatNumber(s.length) + " m");
    }
    s.endSupport = EndSupport::New(supports, {"simple", "clamped", "pinned"},
        "the beam is weightless and dry (no water to float on), so springs alone would not carry it");

    const Dictionary& platen = props.subDict("platen");
    platen.checkKeys({"diameter", "speed", "rampTime", "initialGap"});
    s.platenDiameter = positiveEntry(platen, "diameter");
    s.platenSpeed = positiveEntry(platen, "speed");
    if (options.platenSpeed > 0.0)
    {
        s.platenSpeed = options.platenSpeed;
    }
    s.platenRampTime = platen.getScalarOrDefault("rampTime", 0.0);
    if (s.platenRampTime < 0.0)
    {
        platen.fail("rampTime", "must not be negative");
    }
    s.initialGap = platen.getScalarOrDefault("initialGap", 0.0);
    if (s.initialGap < 0.0)
    {
        platen.fail("initialGap", "must not be negative");
    }

    const Dictionary& packing = props.subDict("packing");
    packing.checkKeys({"particleDiameter", "quickParticleDiameter", "radiusSpread", "solidFraction", "seed"});
    const double standard = positiveEntry(packing, "particleDiameter");
    const double quick = positiveEntry(packing, "quickParticleDiameter");
    s.particleDiameter = options.quick ? quick : standard;
    if (s.particleDiameter > s.thickness)
    {
        packing.fail(options.quick ? "quickParticleDiameter" : "particleDiameter",
                     formatNumber(s.particleDiameter) + " m does not fit in a beam " + formatNumber(s.thickness) + " m thick");
    }
    const RandomPackingChoice choice = RandomPackingChoice::read(packing);
    s.radiusSpread = choice.radiusSpread;
    s.solidFraction = choice.solidFraction;
    s.seed = choice.seed;
    if (s.endSupport->name() != "simple" && 0.5 * (s.length - s.span) < s.particleDiameter)
    {
        supports.fail("endSupport", s.endSupport->name() + " holds the ends by the particles beyond the support "
            "axes, and the beam reaches " + formatNumber(0.5 * (s.length - s.span)) + " m past each: at least "
            "one particle diameter (" + formatNumber(s.particleDiameter) + " m) is needed; shorten supports.span "
            "or lengthen beam.length");
    }

    const Dictionary& target = props.subDict("targetStrength");
    target.checkKeys({"coefficient", "exponent"});
    s.targetCoefficient = positiveEntry(target, "coefficient");
    s.targetExponent = target.getScalar("exponent");

    s.loading = PlatenLoadingControl::forBeamTest(caseDir, props, s.platenSpeed, s.initialGap, options.steps);
    return s;
}


double ThreePointBendingSettings::flexuralStrength(double force) const
{
    return 3.0 * force * span / (2.0 * width * thickness * thickness);
}


double ThreePointBendingSettings::platenTravel(double t, double rampTime) const
{
    return t < rampTime ? 0.5 * platenSpeed * t * t / rampTime : platenSpeed * (t - 0.5 * rampTime);
}


double ThreePointBendingSettings::targetStrength() const
{
    return targetCoefficient * std::pow(length * width * thickness, targetExponent);
}


ThreePointBendingScene::ThreePointBendingScene(MPI_Comm comm, const ThreePointBendingOptions& options)
:
    context_(comm, options.caseDir, application),
    options_(options),
    icePropertiesFile_(options.quick ? "constant/iceProperties.quick" : "constant/iceProperties")
{
    ice_ = IceProperties::read(context_.path(icePropertiesFile_));
    settings_ = ThreePointBendingSettings::read(options_.caseDir, options_);
}


ThreePointBendingScene::~ThreePointBendingScene() = default;




long ThreePointBendingScene::rampSteps() const
{
    return std::max(1L, std::lround(settings_.platenRampTime / body_.dt));
}


void ThreePointBendingScene::buildParticles()
{
    RandomPackingSpec spec;
    spec.lo = Vec3::Zero();
    spec.hi = Vec3(settings_.length, settings_.width, settings_.thickness);
    spec.particleCount = particleCountForDiameter
    (
        spec.lo, spec.hi, settings_.particleDiameter, settings_.radiusSpread, settings_.solidFraction
    );
    spec.radiusSpread = settings_.radiusSpread;
    spec.targetSolidFraction = settings_.solidFraction;
    spec.seed = settings_.seed;
    body_ = buildBondedBody(spec, ice_, context_.path(icePropertiesFile_), {},
                            [this](const std::string& l) { context_.log(l); }, settings_.loading.inertiaScaling);

    const double halfSlab = settings_.particleDiameter;
    const double midHeight = 0.5 * settings_.thickness;
    gaugeOfTag_.assign(body_.particles.size(), Gauge::none);
    double zMid = 0.0, zSupports = 0.0;
    long nMid = 0, nSupports = 0;
    for (std::size_t k = 0; k < body_.particles.size(); ++k)
    {
        const Vec3& x = body_.particles[k].position;
        const bool overSupport = std::abs(x.x() - settings_.supportX(0)) < halfSlab
            || std::abs(x.x() - settings_.supportX(1)) < halfSlab;
        if (std::abs(x.x() - 0.5 * settings_.length) < halfSlab && x.z() < midHeight)
        {
            gaugeOfTag_[k] = Gauge::midspan;
            zMid += x.z();
            ++nMid;
        }
        else if (overSupport && x.z() > midHeight)
        {
            gaugeOfTag_[k] = Gauge::supports;
            zSupports += x.z();
            ++nSupports;
        }
    }
    if (nMid == 0 || nSupports == 0)
    {
        throw InputError(context_.path("constant/bendingProperties"), "packing.particleDiameter",
            "the beam is too coarse to measure its deflection (no particles at mid-span or over a support)");
    }
    midspanHeight0_ = zMid / nMid;
    supportsHeight0_ = zSupports / nSupports;

    // The end support: the platen pushes down (-z); clamped and pinned hold
    // the particles beyond the support axes (pads), simple rests the beam on
    // rollers of supports.diameter at the axes.
    ends_.loadAxis = 2;
    ends_.pushSign = -1;
    ends_.supportX[0] = settings_.supportX(0);
    ends_.supportX[1] = settings_.supportX(1);
    ends_.rollerDiameter = settings_.supportDiameter;
    ends_.contactStiffness = body_.contact.normalStiffness;
    ends_.contactDamping = body_.contact.normalDamping;
    ends_.bodyLo = spec.lo;
    ends_.bodyHi = spec.hi;
    ends_.density = ice_.material.density;
    ends_.particles = body_.particles;
    ends_.endOfTag.assign(body_.particles.size(), -1);
    for (std::size_t k = 0; k < body_.particles.size(); ++k)
    {
        const double x = body_.particles[k].position.x();
        ends_.endOfTag[k] = x < ends_.supportX[0] ? 0 : x > ends_.supportX[1] ? 1 : -1;
    }
}


void ThreePointBendingScene::writeLiggghtsInputs() const
{
    if (context_.rank() != 0)
    {
        return;
    }
    const ThreePointBendingSettings& s = settings_;
    // Room for the beam's halves to swing down and for pieces to fly (the
    // far field stops them at 0.3 m, stopEjecta).
    const double margin = 0.5;
    writeLiggghtsData
    (
        context_.path("DEM/packing.data"),
        "three-point bending beam packing written by threePointBendingDEM",
        body_.particles,
        ice_.material.density,
        Vec3(-margin, -margin, -s.supportDiameter - s.loading.maxTravel - margin),
        Vec3(s.length + margin, s.width + margin, s.thickness + s.initialGap + s.platenDiameter + margin),
        2,
        [this](const ParticleSpec& p)
        {
            const bool pad = ends_.endOfTag[&p - body_.particles.data()] >= 0;
            return pad && !settings_.endSupport->padsIntegrated() ? fixedType : mobileType;
        }
    );
    const double overhang = 0.02;   // the cylinders reach past the beam's sides
    const Vec3 across(0.0, 1.0, 0.0);
    const double platenRadius = 0.5 * s.platenDiameter;
    writeCylinderStl
    (
        context_.path("DEM/platen.stl"),
        Vec3(0.5 * s.length, -overhang, touchingAxisHeight(body_.particles, 0.5 * s.length, platenRadius, 1) + s.initialGap),
        across, platenRadius, s.width + 2.0 * overhang, 48, "platen"
    );
}


void ThreePointBendingScene::startLiggghts(const Checkpoint* resume)
{

    const double skin = 0.2 * body_.maxRadius();
    const std::string readParticles = resume
        ? "read_restart " + loading_->restartFile(*resume)
        : "read_data " + context_.path("DEM/packing.data");
    ScriptVariables variables
    {
        {"readParticles", "\"" + readParticles + "\""},
        {"platenStl", context_.path("DEM/platen.stl")},
        {"ghostCutoff", exactNumber(bondGhostCutoff(ice_, body_.maxRadius(), skin))},
        {"neighbourSkin", exactNumber(skin)},
        {"dt", exactNumber(body_.dt)},
        {"platenSpeed", exactNumber(settings_.platenSpeed)},
        {"platenRampSteps", std::to_string(rampSteps())},
        {"forceSampleSteps", std::to_string(forceSampleSteps())}
    };
    const ScriptVariables contactVars = contactVariables(body_.contact);
    variables.insert(variables.end(), contactVars.begin(), contactVars.end());
    lmp_ = context_.startLiggghts(variables, "DEM/in.threePointBending");
    LiggghtsInstance& lmp = *lmp_;
    EndSupport& support = *settings_.endSupport;
    support.defineForces(lmp, context_, ends_);
    forces_ = attachIceBonds(lmp, ice_, body_, *loading_, resume, [&] { support.defineMotion(lmp, ends_); });
    context_.log("End support " + support.description());
}


long ThreePointBendingScene::forceSampleSteps() const
{
    // The steps between two of PlatenLoading's force samples.
    const PlatenLoadingControl& c = settings_.loading;
    return std::max(1L, std::lround(c.sampleInterval / (c.speed * body_.dt)));
}


double ThreePointBendingScene::platenForce() const
{
    // Averaged over the steps since the last sample (fix forceAverage): the
    // platen's contacts chatter at kHz, which single steps would alias. The
    // beam pushes the descending platen up (+z).
    return lmp_->fix("forceAverage").compute_vector(0);
}


double ThreePointBendingScene::supportReaction() const
{
    // Averaged over the steps since the last sample, as the platen force.
    return settings_.endSupport->reaction(context_.comm());
}


double ThreePointBendingScene::midspanDeflection() const
{
    const LAMMPS_NS::Atom& atom = *lmp_->engine().atom;
    double local[4] = {0.0, 0.0, 0.0, 0.0};     // sum z and count: mid-span, supports
    for (int i = 0; i < atom.nlocal; ++i)
    {
        const Gauge g = gaugeOfTag_[atom.tag[i] - 1];
        if (g != Gauge::none)
        {
            const int k = g == Gauge::midspan ? 0 : 2;
            local[k] += atom.x[i][2];
            local[k + 1] += 1.0;
        }
    }
    double total[4];
    MPI_Allreduce(local, total, 4, MPI_DOUBLE, MPI_SUM, context_.comm());
    return (midspanHeight0_ - total[0] / total[1]) - (supportsHeight0_ - total[2] / total[3]);
}


long ThreePointBendingScene::stopEjecta()
{
    const double clearance = 0.3;
    const ThreePointBendingSettings& s = settings_;
    return stopParticlesOutside
    (
        *lmp_,
        Vec3(-clearance, -clearance, -s.supportDiameter - s.loading.maxTravel - clearance),
        Vec3(s.length + clearance, s.width + clearance, s.thickness + clearance),
        fixedType
    );
}


Provenance ThreePointBendingScene::inputs() const
{
    Provenance p;
    p.add("application", application);
    p.addDictionaryFile(icePropertiesFile_, context_.path(icePropertiesFile_));
    p.addDictionaryFile("constant/bendingProperties", context_.path("constant/bendingProperties"), {"targetStrength"});
    p.addDictionaryFile("system/controlDict", context_.path("system/controlDict"), {"writeInterval", "checkpointInterval", "vtkFormat"});
    p.addFileContent("DEM/in.threePointBending", context_.path("DEM/in.threePointBending"));
    p.add("command line -thickness", options_.thickness > 0.0 ? shortestNumber(options_.thickness) : "not given");
    p.add("command line -platenSpeed", options_.platenSpeed > 0.0 ? shortestNumber(options_.platenSpeed) : "not given");
    p.add("command line -quick", options_.quick ? "yes" : "no");
    return p;
}


void ThreePointBendingScene::run()
{
    std::ostringstream intro;
    intro << application << ": three-point bending, beam " << settings_.length << " x " << settings_.width
          << " x " << settings_.thickness << " m, span " << settings_.span << " m, particles of "
          << settings_.particleDiameter << " m (" << icePropertiesFile_ << "), case " << options_.caseDir
          << ", " << context_.ranks() << " rank(s)";
    context_.log(intro.str());
    buildParticles();
    loading_ = std::make_unique<PlatenLoading>
    (
        context_, settings_.loading, body_.dt,
        static_cast<long>(body_.particles.size()), fixedType,
        std::vector<std::string>{"midspanDeflection", "supportReaction"}
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
    hooks.extras = [this] { return std::vector<double>{midspanDeflection(), supportReaction()}; };
    hooks.stopEjecta = [this] { return stopEjecta(); };
    hooks.failure = [this] { return forces_.failure(); };
    loading_->run(*lmp_, *forces_.bonds, hooks, [this] { writeSummary(); });
    loading_->logEnd();
}


void ThreePointBendingScene::writeSummary() const
{
    const CsvWriter& curve = loading_->curve();
    const BreakageRecord& breaks = loading_->breakage();
    const LoadingState& state = loading_->state();
    if (context_.rank() != 0)
    {
        return;
    }
    const ThreePointBendingSettings& s = settings_;
    // The curve's travel column is speed x time; the platen lags it by half
    // the ramp once at speed.
    const double rampTime = rampSteps() * body_.dt;
    std::vector<double> travel, force, deflection;
    for (std::size_t k = 0; k < curve.nRows(); ++k)
    {
        const std::vector<double>& row = curve.row(k);
        travel.push_back(s.platenTravel(row[0], rampTime));
        force.push_back(row[PlatenLoading::forceColumn]);
        deflection.push_back(row[curve.columns().size() - 2]);
    }
    const std::size_t peakIndex = std::max_element(force.begin(), force.end()) - force.begin();
    const double peak = force[peakIndex];
    const double onset = contactOnset(travel, force, 0.01 * peak);
    std::vector<double> displacement;
    for (double t : travel) displacement.push_back(t - onset);
    // Failure load: the highest load, as in the laboratory test. The first
    // major load drop (a tenth of the peak) marks the first crack; the
    // elastic slopes are fitted on the rise to it.
    const FirstPeak first = firstPeak(displacement, force, 0.1);
    const auto riseEnd = static_cast<std::ptrdiff_t>(first.index) + 1;
    const std::vector<double> riseForce(force.begin(), force.begin() + riseEnd);
    const ForceCurveResult platenFit = analyseForceCurve
    (
        std::vector<double>(displacement.begin(), displacement.begin() + riseEnd), riseForce
    );
    const ForceCurveResult deflectionFit = analyseForceCurve
    (
        std::vector<double>(deflection.begin(), deflection.begin() + riseEnd), riseForce
    );
    const double beamStiffness = 48.0 * s.secondMomentOfArea() / std::pow(s.span, 3);   // per unit E

    const double strength = s.flexuralStrength(peak);
    const double target = s.targetStrength();
    int centreBreaks = 0;
    for (const BreakEvent& e : breaks.events())
    {
        centreBreaks += std::abs(e.position.x() - 0.5 * s.length) < 0.1 * s.span;
    }

    Json modes;
    modes["tension"] = long(breaks.count(BreakMode::tension));
    modes["shear"] = long(breaks.count(BreakMode::shear));
    modes["twist"] = long(breaks.count(BreakMode::twist));
    modes["bending"] = long(breaks.count(BreakMode::bending));
    Json j;
    j["case"] = "threePointBending";
    j["complete"] = true;
    j["resolution"] = options_.quick ? "quick" : "standard";
    j["thickness_m"] = s.thickness;
    j["length_m"] = s.length;
    j["width_m"] = s.width;
    j["span_m"] = s.span;
    j["end_support"] = s.endSupport->summary();
    j["particle_diameter_m"] = s.particleDiameter;
    j["failure_force_N"] = peak;
    j["travel_at_failure_m"] = displacement[peakIndex];
    j["peak_force_N"] = peak;
    j["first_peak_force_N"] = first.force;
    j["travel_at_first_peak_m"] = first.travel;
    j["flexural_strength_Pa"] = strength;   // 3FL/(2BD^2): the simply supported beam's formula
    // Beam theory for these supports: a clamped span carries twice the
    // simply supported (or pinned) one's load at the same stress.
    const double supportFactor = s.endSupport->name() == "clamped" ? 2.0 : 1.0;
    j["flexural_strength_for_supports_Pa"] = strength / supportFactor;
    j["target_strength_Pa"] = target;
    j["strength_error"] = strength / target - 1.0;
    j["elastic_slope_platen_N_per_m"] = platenFit.elasticSlope;
    j["elastic_slope_platen_fit_R2"] = platenFit.slopeFitR2;
    j["elastic_slope_deflection_N_per_m"] = deflectionFit.elasticSlope;
    j["elastic_slope_deflection_fit_R2"] = deflectionFit.slopeFitR2;
    j["effective_modulus_Pa"] = deflectionFit.elasticSlope / beamStiffness;
    j["effective_modulus_from_platen_Pa"] = platenFit.elasticSlope / beamStiffness;
    j["deflection_at_failure_m"] = deflection[peakIndex];
    j["support_reaction_at_failure_N"] = curve.row(peakIndex).back();
    j["contact_onset_travel_m"] = onset;
    j["kinetic_to_elastic_energy_at_peak"] = state.kineticToElasticAtPeak;
    loading_->addQuasiStaticFigures(j);
    j["broken_bonds"] = long(breaks.size());
    j["broken_bonds_by_mode"] = modes;
    j["share_of_breaks_within_10pct_of_span_from_centre"] = breaks.empty() ? 0.0 : double(centreBreaks) / breaks.size();
    j["platen_speed_m_per_s"] = s.platenSpeed;
    j["platen_ramp_time_s"] = rampTime;
    j["particles"] = long(body_.particles.size());
    j["bonds"] = long(body_.bondStats.totalBonds);
    j["bonds_per_particle"] = body_.bondStats.meanBondsPerParticle;
    j["ejected_particles_stopped"] = long(state.frozenEjecta);
    j["steps"] = state.steps;
    j["dt"] = body_.dt;
    j["ranks"] = long(context_.ranks());
    j["inputs_fingerprint"] = loading_->inputs().fingerprint();
    loading_->addRunCostFigures(j);
    writeFileAtomically(context_.path("postProcessing/summary.json"), jsonText(j));
}

} // namespace iceDEM
