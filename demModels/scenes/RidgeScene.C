#include "RidgeScene.H"
#include "CompactionPlates.H"
#include "CommandLine.H"
#include "Format.H"

#include "AtomicFile.H"
#include "BondBuilder.H"
#include "BondedBody.H"
#include "Dictionary.H"
#include "FixedSetStrength.H"
#include "FreezeBonding.H"
#include "GivenAreaCorrection.H"
#include "IceBondForces.H"
#include "InertiaScalingFix.H"
#include "InputError.H"
#include "Json.H"
#include "LiggghtsInstance.H"
#include "ParticleGather.H"
#include "RandomPacking.H"
#include "RigidSheet.H"
#include "SceneSetup.H"
#include "StlWriter.H"
#include "TimeStep.H"
#include "WaterForces.H"

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

constexpr int mobileType = RidgeLoadTest::mobileType;
constexpr int fixedType = RidgeLoadTest::fixedType;
constexpr int boxTypes = 3;     // 3: the box walls


} // namespace


RidgeSettings RidgeSettings::read(int argc, char** argv)
{
    RidgeSettings s;
    CommandLine("ridgeDEM")
        .text("-case", "DIR", "the case directory (default .)", s.caseDir)
        .choice("-stage", {"assemble", "load", "all"}, "which stage to run (default all)", s.stage)
        .flag("-resume", "load: continue from the last checkpoint", s.resume)
        .parse(argc, argv);
    // At the cfd and vof levels system/controlDict is OpenFOAM's (icePunchFoam, icePunchInterFoam).
    const bool resolved = solvedByOpenFOAM(WaterProperties::readCase(s.caseDir, true).level);
    RidgeSettings fromCase = readCase(s.caseDir, resolved ? "system/loadingDict" : "system/controlDict");
    fromCase.stage = s.stage;
    fromCase.resume = s.resume;
    return fromCase;
}


RidgeSettings RidgeSettings::readCase(const std::string& caseDir, const std::string& controlFile)
{
    RidgeSettings s;
    s.caseDir = caseDir;
    const Dictionary d = Dictionary::readFile(s.caseDir + "/constant/ridgeProperties");
    d.checkKeys({"keel", "box", "consolidatedLayer", "assembly", "ends", "test"});

    // The punch box the keel was built in (a reduced keel for tests needs a smaller one).
    if (d.isDict("box"))
    {
        const Dictionary& box = d.subDict("box");
        box.checkKeys({"length", "width"});
        s.layer.length = box.getPositiveScalarOrDefault("length", s.layer.length);
        s.layer.width = box.getPositiveScalarOrDefault("width", s.layer.width);
    }

    const Dictionary& keel = d.subDict("keel");
    keel.checkKeys({"settledRubble", "trimDepth"});
    const std::string keelFile = keel.getString("settledRubble");
    s.hasKeel = keelFile != "none";
    s.keelFile = !s.hasKeel ? "none" : keelFile.front() == '/' ? keelFile : s.caseDir + "/" + keelFile;
    s.trimDepth = keel.getScalarOrDefault("trimDepth", s.trimDepth);
    if (s.trimDepth < 0.0) keel.fail("trimDepth", "must not be negative");

    const Dictionary& cl = d.subDict("consolidatedLayer");
    cl.checkKeys({"thickness", "particleDiameter", "radiusSpread", "solidFraction", "seed"});
    s.layer.thickness = cl.getScalar("thickness");
    if (s.layer.thickness < 0.0) cl.fail("thickness", "must be 0 (a bare keel) or positive, in m");
    s.layer.particleDiameter = cl.getPositiveScalarOrDefault("particleDiameter", s.layer.particleDiameter);
    const RandomPackingChoice choice = RandomPackingChoice::read(cl);
    s.layer.radiusSpread = choice.radiusSpread;
    s.layer.solidFraction = choice.solidFraction;
    s.layer.seed = choice.seed;
    if (s.layer.thickness > 0.0 && s.layer.thickness < 1.25 * s.layer.particleDiameter)
    {
        cl.fail("thickness", "a layer thinner than 1.25 particle diameters cannot bend; "
                "use smaller particles or 0 for no layer");
    }

    const Dictionary& a = d.subDict("assembly");
    a.checkKeys({"pressDepth", "pressSpeed", "relaxTime", "youngsModulus", "dampingAlpha", "stiffenTime",
                 "layerHold"});
    s.pressDepth = a.getScalarOrDefault("pressDepth", s.pressDepth);
    if (s.pressDepth < 0.0) a.fail("pressDepth", "must not be negative");
    s.pressSpeed = a.getPositiveScalarOrDefault("pressSpeed", s.pressSpeed);
    s.relaxTime = a.getScalarOrDefault("relaxTime", s.relaxTime);
    if (s.relaxTime < 0.0) a.fail("relaxTime", "must not be negative");
    s.assemblyYoungsModulus = a.getPositiveScalarOrDefault("youngsModulus", s.assemblyYoungsModulus);
    s.stiffenTime = a.getScalarOrDefault("stiffenTime", s.stiffenTime);
    if (s.stiffenTime < 0.0) a.fail("stiffenTime", "must not be negative (s; 0: bond at the soft contacts' overlaps)");
    s.assemblyDampingAlpha = a.getScalarOrDefault("dampingAlpha", s.assemblyDampingAlpha);
    // pressed: the layer stays where it was pressed while the contacts stiffen; balanced: it moves as a
    // free rigid sheet until the keel's push balances its weight, buoyancy and the lid's hold
    s.layerHeldWherePressed = a.getChoiceOrDefault("layerHold", {"pressed", "balanced"}, "pressed") == "pressed";
    if (s.assemblyDampingAlpha < 0.0 || s.assemblyDampingAlpha > 1.0)
    {
        a.fail("dampingAlpha", "expected a hysteretic alpha in [0, 1]");
    }

    if (!s.hasKeel && s.layer.thickness <= 0.0)
    {
        keel.fail("settledRubble", "none (no keel) needs a consolidated layer: consolidatedLayer.thickness is 0");
    }

    // The ends' pads are made with the ridge (fixedLength); how they are held
    // (endSupport) is the loading stage's.
    const Dictionary& ends = d.subDict("ends");
    ends.checkKeys({"fixedLength", "endSupport", "floatingCoeffs"});
    s.fixedEndLength = ends.getScalar("fixedLength");
    if (s.fixedEndLength < 0.0 || 2.0 * s.fixedEndLength >= s.layer.length)
    {
        ends.fail("fixedLength", "expected 0 <= fixedLength < half the beam length");
    }

    const Dictionary& t = d.subDict("test");
    t.checkKeys({"type", "platenLength", "platenHeight", "settleTime", "speed", "initialGap",
                 "referenceFlexuralStrength", "inertiaScaling"});
    s.test = t.getChoice("type", RidgeLoadTest::names());
    s.loading.readInertiaScaling(t);
    if (s.loading.inertiaScaling != 1.0 && !RidgeLoadTest::New(s.test, s)->integratesParticles())
    {
        t.fail("inertiaScaling", formatNumber(s.loading.inertiaScaling) + " is not allowed here (only 1): "
               + s.test + " moves the layer rigidly and integrates no particle's motion, and its force is the sum "
               "of the layer's forces: there is no inertia to scale");
    }
    const WaterLevel level = WaterProperties::readCase(s.caseDir, true).level;
    if (s.loading.inertiaScaling != 1.0 && solvedByOpenFOAM(level))
    {
        t.fail("inertiaScaling", formatNumber(s.loading.inertiaScaling) + " is not allowed at the "
               + toString(level) + " level (only 1): OpenFOAM's water exchanges momentum with the particles every coupling step and its own "
               "inertia is not scaled, so the coupled dynamics would be neither the true one nor a uniformly "
               "slowed one (not validated; in still water, ridgeDEM, the added mass is scaled with the particles')");
    }
    if (t.found("referenceFlexuralStrength"))
    {
        s.referenceFlexuralStrength = t.getPositiveScalarOrDefault("referenceFlexuralStrength", 1.0);
    }
    s.platenLength = t.getPositiveScalarOrDefault("platenLength", s.platenLength);
    s.platenHeight = t.getPositiveScalarOrDefault("platenHeight", s.platenHeight);
    s.settleTime = t.getScalarOrDefault("settleTime", s.settleTime);
    if (s.settleTime < 0.0) t.fail("settleTime", "must not be negative");
    s.loading.speed = t.getPositiveScalarOrDefault("speed", s.loading.speed);
    s.loading.initialGap = t.getScalarOrDefault("initialGap", 0.002);
    if (s.loading.initialGap < 0.0) t.fail("initialGap", "must not be negative");
    if (RidgeLoadTest::New(s.test, s)->needsLayer() && s.layer.thickness <= 0.0)
    {
        t.fail("type", s.test + " tests the bond between keel and consolidated layer: "
               "consolidatedLayer.thickness must be positive");
    }
    if (RidgeLoadTest::New(s.test, s)->needsLayer() && !s.hasKeel)
    {
        t.fail("type", s.test + " tests the bond between keel and consolidated layer: "
               "keel.settledRubble must name a keel");
    }
    s.endSupport = RidgeLoadTest::New(s.test, s)->needsLayer()
        ? EndSupport::New(ends, {"clamped"}, s.test + " holds the whole keel fixed, so its ends are held with it")
        : EndSupport::New(ends);
    if (s.fixedEndLength <= 0.0 && (s.endSupport->name() == "pinned" || s.endSupport->name() == "floating"))
    {
        ends.fail("fixedLength", "0 leaves no end pads for endSupport " + s.endSupport->name());
    }

    s.controlFile = controlFile;
    const Dictionary control = Dictionary::readFile(s.caseDir + "/" + controlFile);
    control.checkKeys
    ({
        "application", "maxTravel", "minTravel", "rampTravel", "blowUpFactor", "maxParticleSpeed", "stopAfterHalfLoad", "travelAfterHalfLoad",
        "sampleInterval", "writeInterval", "checkpointInterval", "maxKineticToWorkRatio", "vtkFormat"
    });
    s.loading.readControl(control);
    return s;
}


RidgeScene::RidgeScene(MPI_Comm comm, const RidgeSettings& settings, const ExternalWater* externalWater)
:
    context_(comm, settings.caseDir, externalWater ? externalWater->application : "ridgeDEM"),
    settings_(settings),
    test_(RidgeLoadTest::New(settings_.test, settings_)),
    externalWater_(externalWater)
{
    ice_ = IceProperties::read(context_.path("constant/iceProperties"));
    requireFreezeBondStrengthsPerBond(ice_, context_.path("constant/iceProperties"));
    freezeBondProperties_ = FreezeBondProperties::read(context_.path("constant/freezeBondProperties"));
    freezeBondProperties_.checkIce(ice_, context_.path("constant/iceProperties"));
    if (!dynamic_cast<const GivenAreaCorrection*>(&freezeBondProperties_.areaCorrection()))
    {
        throw InputError(context_.path("constant/freezeBondProperties"), "areaCorrection.model",
            "a ridge needs `given` (c_f of its keel, see the keel's summary.json); the block shapes "
            "that heatBalance needs are not kept with the settled keel");
    }
    water_ = WaterProperties::readCase(settings_.caseDir, true);
    const bool loads = settings_.stage == "load" || settings_.stage == "all";
    const std::string coupling = context_.path("constant/couplingProperties");
    const std::string level = toString(water_.level);
    const auto loadingApplication = [](WaterLevel l) { return l == WaterLevel::vof ? "icePunchInterFoam" : "icePunchFoam"; };
    if (externalWater_ && externalWater_->name != level)
    {
        throw InputError(coupling, "waterLevel", "'" + level + "': " + externalWater_->application
            + " solves the water of the loading stage at the " + externalWater_->name + " level; allowed here: "
            + externalWater_->name + " (hydrostatic: ridgeDEM, cfd: icePunchFoam, vof: icePunchInterFoam)");
    }
    if (!externalWater_ && solvedByOpenFOAM(water_.level) && loads)
    {
        throw InputError(coupling, "waterLevel", level + ": ridgeDEM loads in still (hydrostatic) water and only "
            "assembles at the " + level + " level (-stage assemble); the loading stage at the " + level
            + " level runs in " + loadingApplication(water_.level) + " (cases/rubblePunch: ./Allrun -water " + level + ")");
    }
    if (!externalWater_ && water_.level != WaterLevel::hydrostatic && !solvedByOpenFOAM(water_.level))
    {
        throw InputError(coupling, "waterLevel", "ridgeDEM runs in still water: allowed here: hydrostatic "
            "(cfd: icePunchFoam, vof: icePunchInterFoam; see coupling/README.md)");
    }
    if (solvedByOpenFOAM(water_.level) && !water_.hydrostatic.floatingSurface && settings_.stage != "load")
    {
        throw InputError(coupling, "hydrostatic", "at the " + level + " level the ridge is still assembled in still "
            "water where it floats: needs hydrostatic { surfaceLevel floating; rho; mu; } (the level of the "
            "fluid mesh's surface)");
    }
}


RidgeScene::~RidgeScene() = default;




void RidgeScene::run()
{
    context_.log("ridgeDEM: " + settings_.test + " test of a ridge, case " + settings_.caseDir + ", "
        + std::to_string(context_.ranks()) + " rank(s)");
    if (settings_.stage == "assemble" || settings_.stage == "all")
    {
        if (settings_.resume && std::filesystem::exists(context_.path("DEM/ridge.h5")))
        {
            context_.log("Resuming: the ridge is already assembled (DEM/ridge.h5)");
        }
        else
        {
            assemble();
        }
    }
    if (settings_.stage == "load" || settings_.stage == "all")
    {
        load();
    }
}


void RidgeScene::chooseContactsAndStep
(
    const std::vector<ParticleSpec>& particles,
    const IceProperties& ice,
    double inertiaScaling
)
{
    double minRadius = HUGE_VAL, meanDiameter = 0.0;
    for (const ParticleSpec& p : particles)
    {
        minRadius = std::min(minRadius, p.radius);
        meanDiameter += 2.0 * p.radius / particles.size();
    }
    const double minMass = ice.material.density * 4.0 / 3.0 * M_PI * std::pow(minRadius, 3);
    contact_ = ContactParameters::of(ice, meanDiameter, minMass);
    const TimeStepLimits limits = timeStepLimits(ice, minRadius, ice.maxBondsPerParticle, inertiaScaling);
    dt_ = chooseTimeStep(ice, limits, context_.path("constant/iceProperties"));
    particleCount_ = static_cast<long>(particles.size());
}


// The keel settled, and the layer was pressed into it, with contacts far
// softer than the ice's, so touching spheres overlap hundreds of times deeper
// than the ice's stiffness allows. A bond made over such an overlap cancels
// the contact while it holds; once broken, its pair would get the ice's
// contact force on that overlap: kilonewtons, against freeze-bonds that break
// at newtons, and the keel would shatter at the first break. So before any
// bond is made the contacts (and the blocks' own bonds) stiffen to the ice's
// in geometric stages, the keel relaxing at each under the held layer.
void RidgeScene::stiffenContacts(const std::vector<ParticleSpec>& particles)
{
    constexpr int stages = 12;
    constexpr int lidBackOffsPerStage = 10;
    const OverlapStatistics before = overlapStatistics(particles, allPositionsByTag(*lmp_));
    const double soft = settings_.assemblyYoungsModulus;
    const double hard = ice_.material.youngsModulus;
    const long layerCount = static_cast<long>(particles.size()) - (layerFirstTag_ - 1);
    std::unique_ptr<RigidSheet> sheet;
    if (!settings_.layerHeldWherePressed && layerCount > 0)
    {
        // The layer presses the keel with the compaction's hold (the lid's load,
        // which the lid then leaves to it) besides its own weight.
        sheet = std::make_unique<RigidSheet>(*lmp_, layerFirstTag_, plates_ ? plateHoldLoad_ : 0.0,
                                             settings_.assemblyDampingAlpha);
        if (plates_)
        {
            plates_->place(plates_->bottom(), boxHigh_.z());
        }
        sheet->define();
    }
    // A balanced keel without a layer is held by the lid alone, which backs off one
    // estimated step at a time: from the pressure a deep keel was compacted under
    // (8.6 kPa for the 1.0 m one) one step per stage leaves 5.4 kPa after the twelve.
    const bool lidHolds = plates_ && !sheet && !settings_.layerHeldWherePressed;
    const int chunks = lidHolds ? lidBackOffsPerStage : 1;
    long steps = 0;
    for (int k = 1; k <= stages; ++k)
    {
        const double modulus = soft * std::pow(hard / soft, static_cast<double>(k) / stages);
        const IceProperties stage = ice_.softenedForAssembly(modulus, settings_.assemblyDampingAlpha);
        chooseContactsAndStep(particles, stage);
        setContactStiffness();
        bonds_->changeProperties(stage);
        const long n = std::max(1L, std::lround(settings_.stiffenTime / stages / dt_));
        const long chunkSteps = std::max(1L, n / chunks);
        lmp_->command("run " + std::to_string(chunkSteps));
        for (int c = 1; c < chunks; ++c)
        {
            plates_->backOffLid(plateHoldLoad_, plateMinTop_);
            lmp_->command("run " + std::to_string(chunkSteps) + " pre no post no");
        }
        steps += chunks * chunkSteps;
        const long present = sumOverRanks(context_.comm(), static_cast<long>(lmp_->engine().atom->nlocal));
        if (present != static_cast<long>(particles.size()))
        {
            throw RunError(std::to_string(particles.size() - present) + " particle(s) left the simulation box while"
                " the assembly stiffened the contacts (stage " + std::to_string(k) + " of " + std::to_string(stages)
                + ", E = " + formatNumber(modulus) + " Pa, step " + std::to_string(lmp_->step()) + "): the keel's"
                " soft-contact overlaps released more energy than the plates hold (a keel compacted under a high"
                " hold pressure?)");
        }
        if (plates_ && !sheet)
        {
            // The lid holds the compaction's pressure, not its position: held in
            // place while the contacts stiffen, it would lock in a stress ten times
            // that (7.2 kPa against 0.6) that the bonds take at the release.
            plates_->backOffLid(plateHoldLoad_, plateMinTop_);
        }
    }
    if (sheet)
    {
        std::ostringstream moved;
        moved << "Layer balanced on the stiffening keel (assembly.layerHold balanced): moved "
              << std::abs(sheet->travel()) * 1e3 << (sheet->travel() < 0.0 ? " mm down" : " mm up")
              << ", net force " << sheet->netForce() << " N, speed " << sheet->speed() << " m/s at the end";
        layerRise_ = sheet->travel();
        sheet->release();
        context_.log(moved.str());
    }
    const OverlapStatistics after = overlapStatistics(particles, allPositionsByTag(*lmp_));
    std::ostringstream msg;
    msg << "Contacts stiffened from E = " << soft << " to " << hard << " Pa over " << settings_.stiffenTime
        << " s (" << stages << " stages, " << steps << " steps): touching pairs between blocks " << before.touchingPairs
        << " -> " << after.touchingPairs << ", mean overlap " << before.meanOverlap * 1e6 << " -> "
        << after.meanOverlap * 1e6 << " um, largest " << before.maxOverlap * 1e6 << " -> "
        << after.maxOverlap * 1e6 << " um";
    context_.log(msg.str());
}


void RidgeScene::setContactStiffness()
{
    const auto matrix = [](double value) { return typePairMatrix(value, value); };
    lmp_->command("fix m1 all property/global kn peratomtypepair 3 " + matrix(contact_.normalStiffness));
    lmp_->command("fix m2 all property/global kt peratomtypepair 3 " + matrix(contact_.tangentialStiffness));
    lmp_->command("fix m3 all property/global gamman_abs peratomtypepair 3 " + matrix(contact_.normalDamping));
    lmp_->command("fix m4 all property/global gammat_abs peratomtypepair 3 " + matrix(contact_.tangentialDamping));
    lmp_->command("timestep " + exactNumber(dt_));
}


void RidgeScene::startLiggghts
(
    const std::vector<ParticleSpec>& particles,
    const std::vector<int>& types,
    const IceProperties& ice,
    const std::string& readParticles,
    double dt
)
{
    double maxRadius = 0.0, top = 0.0;
    for (const ParticleSpec& p : particles)
    {
        maxRadius = std::max(maxRadius, p.radius);
        top = std::max(top, p.position.z() + p.radius);
    }

    const double margin = 0.05;
    boxLow_ = Vec3(-margin, -margin, -margin);
    boxHigh_ = Vec3(settings_.layer.length + margin, settings_.layer.width + margin, top + settings_.loading.maxTravel + 0.5);
    if (context_.rank() == 0)
    {
        std::filesystem::create_directories(context_.path("DEM"));
        std::filesystem::create_directories(context_.path("postProcessing"));
        writeLiggghtsData
        (
            context_.path("DEM/ridge.data"), "ridge written by ridgeDEM", particles, ice.material.density, boxLow_, boxHigh_,
            boxTypes, [&](const ParticleSpec& p) { return types[&p - particles.data()]; }
        );
    }
    MPI_Barrier(context_.comm());

    const double skin = 0.2 * maxRadius;
    ScriptVariables variables
    {
        {"readParticles", "\"" + readParticles + "\""},
        {"ghostCutoff", exactNumber(bondGhostCutoff(ice, maxRadius, skin))},
        {"neighbourSkin", exactNumber(skin)},
        {"dt", exactNumber(dt)},
        {"gravity", exactNumber(water_.gravity.norm())},
        {"boxWidth", exactNumber(settings_.layer.width)},
        {"layerFirstTag", std::to_string(layerFirstTag_)}
    };
    const ScriptVariables contacts = boxContactVariables(contact_);
    variables.insert(variables.end(), contacts.begin(), contacts.end());
    lmp_ = context_.startLiggghts(variables, "DEM/in.ridge");
}


void RidgeScene::requireInsideBox(const SavedRubble& keel) const
{
    // A keel of another box would reach LIGGGHTS as "Did not assign all atoms correctly".
    const double tolerance = 1e-9;
    for (const SavedParticle& p : keel.particles)
    {
        const Vec3& x = p.position;
        if (x.x() < -tolerance || x.x() > settings_.layer.length + tolerance
         || x.y() < -tolerance || x.y() > settings_.layer.width + tolerance)
        {
            std::ostringstream where;
            where << "a particle of the keel " << settings_.keelFile << " lies at (" << x.x() << ", " << x.y()
                  << "), outside this case's box of " << settings_.layer.length << " x " << settings_.layer.width
                  << " m: the keel was built in another box (box.length/box.width must be the keel's)";
            throw InputError(context_.path("constant/ridgeProperties"), "box", where.str());
        }
    }
}


void RidgeScene::assemble()
{
    const auto wallStart = std::chrono::steady_clock::now();
    if (settings_.hasKeel && !std::filesystem::exists(settings_.keelFile))
    {
        throw InputError(context_.path("constant/ridgeProperties"), "keel.settledRubble",
            "'" + settings_.keelFile + "' does not exist: build the keel first (its rubble case's "
            "./Allrun, or rubbleDEM -stage settle and -stage compact)");
    }
    // Read once at the start: an edit during the assembly is not what made the ridge.
    const Provenance inputs = assemblyInputs();
    // Without a keel (settledRubble none) the layer alone, placed 0.5 m above
    // the box's floor (where a 0.5 m keel's bottom floats), floats in the water.
    SavedRubble keel;
    bool compacted = false;
    if (settings_.hasKeel)
    {
        keel = SavedRubble::read(settings_.keelFile);
        compacted = keel.kind == SavedRubble::compactedRubble;
        if (keel.kind != SavedRubble::settledRubble && !compacted)
        {
            throw InputError(settings_.keelFile, "kind", "holds " + (keel.kind.empty() ? std::string("no kind")
                : "a " + keel.kind) + ", where a keel must be a settled or a compacted rubble (rubbleDEM -stage settle "
                "or -stage compact)");
        }
        requireInsideBox(keel);
        // The keel's overlaps are forces only at the modulus it came to rest
        // with: pressed or stiffened from another, it would jump apart or sag.
        if (std::isfinite(keel.contactYoungsModulus) && keel.contactYoungsModulus != settings_.assemblyYoungsModulus)
        {
            throw InputError(context_.path("constant/ridgeProperties"), "assembly.youngsModulus",
                formatNumber(settings_.assemblyYoungsModulus) + " Pa, but the keel " + settings_.keelFile
                + " came to rest with contacts at " + formatNumber(keel.contactYoungsModulus) + " Pa (its rubble case's "
                "settling or compaction youngsModulus): set the same modulus here");
        }
    }
    const RidgeLayout layout = settings_.hasKeel
        ? assembleRidge(keel.particles, settings_.layer, settings_.trimDepth)
        : assembleLayerAlone(settings_.layer, 0.5);
    layerFirstTag_ = layout.keelParticles + 1;
    const int layerCount = static_cast<int>(layout.particles.size()) - layout.keelParticles;

    // The water stands where the finished ridge floats.
    std::vector<ParticleSpec> pressed = layout.particles;
    for (std::size_t k = layout.keelParticles; k < pressed.size(); ++k)
    {
        pressed[k].position.z() -= settings_.pressDepth;
    }
    HydrostaticWaterParameters waterParameters = water_.hydrostatic;
    if (waterParameters.floatingSurface)
    {
        waterParameters.surfaceLevel =
            floatingWaterLevel(pressed, ice_.material.density / waterParameters.density);
    }
    {
        std::ostringstream msg;
        msg << "Keel " << settings_.keelFile << ": " << keel.particles.size() << " particles, top "
            << layout.keelTop << " m, bottom " << layout.keelBottom << " m, saved water level "
            << keel.waterLevel << " m; " << layout.trimmedParticles << " particles trimmed from the top "
            << settings_.trimDepth << " m; consolidated layer " << settings_.layer.thickness << " m of "
            << layerCount << " particles from z = " << layout.clBottom << " m; water surface at "
            << waterParameters.surfaceLevel << " m (" << (waterParameters.floatingSurface ? "where the ridge floats" : "given") << ")";
        context_.log(msg.str());
    }

    // Pressing: the keel with soft contacts and unbreakable blocks (as it
    // settled), the layer rigid (fixed type, moved by LIGGGHTS).
    const IceProperties soft = ice_.softenedForAssembly(settings_.assemblyYoungsModulus, settings_.assemblyDampingAlpha);
    std::vector<int> types(layout.particles.size(), mobileType);
    // (A layer alone is left mobile: LIGGGHTS needs a particle of type 1,
    // and it is not pressed.)
    for (std::size_t k = layout.keelParticles; k < types.size(); ++k)
    {
        types[k] = layout.keelParticles > 0 ? fixedType : mobileType;
    }
    chooseContactsAndStep(layout.particles, soft);
    startLiggghts(layout.particles, types, soft, "read_data " + context_.path("DEM/ridge.data"), dt_);

    waterForces_ = std::make_unique<WaterForces>(*lmp_, HydrostaticWater(waterParameters));
    waterForces_->defineForceFix();
    if (compacted)
    {
        // The compaction's plates hold the keel while it is pressed, stiffened and
        // bonded (scenes.md section 5: the freeze-bonds form under the compaction
        // pressure); the ridge is saved without them.
        plates_ = std::make_unique<CompactionPlates>
        (
            *lmp_, CompactionPlateLaw{contact_.normalStiffness, contact_.normalDamping}
        );
        plates_->define();
        plates_->place(keel.plateBottom, keel.plateTop);
        plateHoldLoad_ = keel.plateHoldPressure*settings_.layer.length*settings_.layer.width;
        plateMinTop_ = keel.plateTop;
    }
    bonds_ = IceBondForces::define(*lmp_, soft);
    waterForces_->defineAddedMassFix();
    lmp_->command("run 0");
    std::vector<ParticleSpec> keelOnly(layout.particles.begin(), layout.particles.begin() + layout.keelParticles);
    std::vector<BondPair> blockBonds;
    for (const BondPair& b : BondBuilder(soft).build(keelOnly))
    {
        if (b.family == BondFamily::ice) blockBonds.push_back(b);
    }
    bonds_->createBonds(layout.particles, blockBonds);
    lmp_->command("run 0");

    // A layer alone has nothing to be pressed into or to settle under it.
    const bool press = layerCount > 0 && layout.keelParticles > 0;
    const long pressSteps = press
        ? std::lround(settings_.pressDepth / (settings_.pressSpeed * dt_)) : 0;
    const long relaxSteps = press ? std::lround(settings_.relaxTime / dt_) : 0;
    if (pressSteps > 0)
    {
        context_.log("Pressing the layer " + formatNumber(settings_.pressDepth * 1e3) + " mm into the keel at "
            + formatNumber(settings_.pressSpeed) + " m/s (" + std::to_string(pressSteps) + " steps of " + formatNumber(dt_) + " s)");
        lmp_->command("fix pressLayer layer move linear 0 0 " + exactNumber(-settings_.pressSpeed));
        lmp_->command("run " + std::to_string(pressSteps));
        lmp_->command("unfix pressLayer");
    }
    if (relaxSteps > 0)
    {
        context_.log("Keel settling under the held layer for " + formatNumber(settings_.relaxTime) + " s ("
            + std::to_string(relaxSteps) + " steps)");
        lmp_->command("velocity layer set 0 0 0");
        lmp_->command("run " + std::to_string(relaxSteps));
    }

    if (settings_.stiffenTime > 0.0 && layout.keelParticles > 0)     // a layer alone has no contacts between blocks
    {
        stiffenContacts(layout.particles);
    }

    // What the bonds are made under, for postProcessing/assembly.json.
    Json assembly;
    assembly["layer_hold"] = settings_.layerHeldWherePressed ? "pressed" : "balanced";
    assembly["layer_rise_during_stiffening_m"] = layerRise_;
    if (plates_)
    {
        const PlateLoads loads = plates_->loads();
        const double area = settings_.layer.length*settings_.layer.width;
        assembly["floor_plate_Pa"] = loads.floor/area;
        assembly["lid_Pa"] = loads.lid/area;
        std::ostringstream msg;
        msg << "Compacted keel held between plates at z = " << plates_->bottom() << " and " << plates_->top()
            << " m: " << loads.floor/area << " Pa on the floor plate, " << loads.lid/area << " Pa on the lid, "
            << loads.touching << " spheres touching them, when the bonds are made";
        context_.log(msg.str());
    }

    // Bonds at the pressed geometry: ice bonds within blocks and within the
    // layer, freeze-bonds wherever two blocks (or layer and keel) touch, with
    // the confinement of the contact forces they settled with.
    const std::vector<Vec3> positions = allPositionsByTag(*lmp_);
    std::vector<ParticleSpec> now = layout.particles;
    for (std::size_t k = 0; k < now.size(); ++k)
    {
        // Off the side walls: an overlap that the soft assembly contacts
        // allowed would push with thousands of newtons at the ice stiffness.
        now[k].position = positions[k];
        double& y = now[k].position.y();
        y = std::clamp(y, now[k].radius, settings_.layer.width - now[k].radius);
    }
    std::vector<BondPair> iceBonds;
    for (const BondPair& b : BondBuilder(ice_).build(now))
    {
        if (b.family == BondFamily::ice) iceBonds.push_back(b);
    }
    const std::vector<NewFreezeBond> freezeBonds =
        freezeBondsAtContacts(now, ice_, freezeBondProperties_, contact_.normalStiffness);
    const FreezeBondingStatistics freezeStats = freezeBondingStatistics(freezeBonds, now);
    long layerToKeel = 0;
    for (const NewFreezeBond& b : freezeBonds)
    {
        if ((b.pair.i >= layout.keelParticles) != (b.pair.j >= layout.keelParticles)) ++layerToKeel;
    }

    SavedRubble ridge;
    ridge.bonds = newBondStates(iceBonds, now, ice_);
    const std::vector<BondState> freezeStates = freezeBondStates(freezeBonds, now, ice_);
    ridge.bonds.insert(ridge.bonds.end(), freezeStates.begin(), freezeStates.end());
    long fixedEnds = 0;
    for (std::size_t k = 0; k < now.size(); ++k)
    {
        SavedParticle p;
        p.position = now[k].position;
        p.radius = now[k].radius;
        p.density = ice_.material.density;
        p.block = now[k].block;
        const double x = p.position.x();
        const bool atEnd = x - p.radius < settings_.fixedEndLength
            || x + p.radius > settings_.layer.length - settings_.fixedEndLength;
        p.type = atEnd ? fixedType : mobileType;
        fixedEnds += atEnd;
        ridge.particles.push_back(p);
    }
    ridge.time = 0.0;
    ridge.waterLevel = waterParameters.surfaceLevel;
    ridge.provenance = inputs.text();
    ridge.kind = SavedRubble::ridge;
    ridge.description = "ridge assembled by ridgeDEM from " + settings_.keelFile + ": keel trimmed by "
        + formatNumber(settings_.trimDepth) + " m, consolidated layer " + formatNumber(settings_.layer.thickness)
        + " m (block " + std::to_string(layout.clBlock) + "), pressed " + formatNumber(settings_.pressDepth) + " m";

    RidgeGeometry geometry = measureRidge(ridge.particles, layout.clBlock, settings_.layer.length, settings_.layer.width);
    geometry.waterLevel = ridge.waterLevel;
    assembly["freeze_bonds"] = freezeStats.bonds;
    assembly["freeze_bonds_layer_keel"] = layerToKeel;
    assembly["confinement_mean_Pa"] = freezeStats.meanConfinement;
    assembly["confinement_max_Pa"] = freezeStats.maxConfinement;
    if (context_.rank() == 0)
    {
        ridge.write(context_.path("DEM/ridge.h5"));
        writeGeometry(geometry, ridge.particles);
        writeFileAtomically(context_.path("postProcessing/assembly.json"), jsonText(assembly));
    }
    // The load stage reads ridge.h5 on every rank next (-stage all).
    MPI_Barrier(context_.comm());
    std::ostringstream msg;
    msg << "Bonds: " << iceBonds.size() << " ice bonds (blocks and layer), " << freezeStats.bonds
        << " freeze-bonds (" << layerToKeel << " between layer and keel); confinement "
        << freezeStats.meanConfinement * 1e-3 << " kPa mean, " << freezeStats.maxConfinement * 1e-3
        << " kPa max on the real area; effective tensile " << freezeStats.meanEffectiveTensile * 1e-3
        << " kPa, shear " << freezeStats.meanEffectiveShear * 1e-3 << " kPa; particle-level tensile "
        << freezeStats.meanTensile * 1e-3 << " kPa, shear " << freezeStats.meanShear * 1e-3
        << " kPa on the bond area (" << freezeBondProperties_.summary() << "); " << fixedEnds
        << " particles fixed at the ends; depth " << geometry.depth() << " m; assembled in "
        << formatDuration(std::chrono::duration<double>(std::chrono::steady_clock::now() - wallStart).count())
        << "; saved DEM/ridge.h5";
    context_.log(msg.str());

    bonds_.reset();
    plates_.reset();
    waterForces_.reset();
    lmp_.reset();
}


void RidgeScene::writeGeometry(const RidgeGeometry& g, const std::vector<SavedParticle>& bonded) const
{
    std::vector<ParticleSpec> specs;
    std::vector<Vec3> positions;
    for (const SavedParticle& p : bonded)
    {
        specs.push_back({p.position, p.radius, p.block});
        positions.push_back(p.position);
    }
    const OverlapStatistics atBonding = overlapStatistics(specs, positions);

    // The schema of postProcessing/failureAnalysis.py (postProcessing/README.md).
    Json layers = Json::array({{{"name", "keel"}, {"zBottom", g.keelBottom}, {"zTop", g.keelTop}}});
    if (g.hasLayer())
    {
        layers.push_back({{"name", "consolidatedLayer"}, {"zBottom", g.clBottom}, {"zTop", g.clTop}});
    }
    Json j;
    j["length"] = g.length;
    j["width"] = g.width;
    j["x0"] = 0;
    j["y0"] = 0;
    j["layers"] = layers;
    j["loadX"] = 0.5 * g.length;
    j["loadHalfLength"] = 0.5 * settings_.platenLength;
    j["supports"] = {settings_.fixedEndLength, g.length - settings_.fixedEndLength};
    j["waterLevel"] = g.waterLevel;
    j["particleRadius"] = g.particleRadius;
    j["depth"] = g.depth();
    j["test"] = settings_.test;
    j["overlapsBetweenBlocksAtBonding"] =
    {
        {"touchingPairs", atBonding.touchingPairs},
        {"mean", atBonding.meanOverlap},
        {"max", atBonding.maxOverlap}
    };
    writeFileAtomically(context_.path("postProcessing/geometry.json"), jsonText(j));
}


long RidgeScene::stopParticlesAtBoxEdge()
{
    // A piece that breaks off with its bonds' stored energy can fly over the
    // ridge's fixed ends (seen once in about thirty runs: a CL sphere at 0.6 m/s
    // past the peak) and would leave the box, which stops the run. Gravity
    // would bring it down in the water outside the ridge; instead it is
    // stopped within 20 mm of the box's faces, and counted.
    const Vec3 edge = Vec3::Constant(0.02);
    return stopParticlesOutside(*lmp_, boxLow_ + edge, boxHigh_ - edge, fixedType);
}


double RidgeScene::testForce() const
{
    return test_->force(*lmp_, context_.comm(), layerFirstTag_);
}


std::vector<double> RidgeScene::extraColumns()
{
    // The buoyancy and submerged volume come from the scene's own water
    // fix, or, where the water is external, from the particles' caps below
    // the still surface; the buoyancy share is the same in both.
    const HydrostaticWater& water = waterForces_ ? waterForces_->water() : *stillSurface_;
    double submerged = 0.0, buoyancy = 0.0;
    if (waterForces_)
    {
        const WaterForceTotals totals = waterForces_->totals();
        submerged = totals.submergedVolume;
        buoyancy = totals.buoyancy.z();
    }
    else
    {
        const LAMMPS_NS::Atom& atom = *lmp_->engine().atom;
        const double level = water.parameters().surfaceLevel;
        double local = 0.0;
        for (int i = 0; i < atom.nlocal; ++i)
        {
            local += submergedSphereVolume(atom.radius[i], level - (atom.x[i][2] - atom.radius[i]));
        }
        submerged = sumOverRanks(context_.comm(), local);
        buoyancy = water.buoyancy(submerged);
    }
    if (submergedAtStart_ < 0.0)
    {
        submergedAtStart_ = submerged;
    }
    const double share = water.buoyancy(submerged - submergedAtStart_);
    const double platenBuoyancy = test_->loadingBodyBuoyancy
    (
        water, settings_.loading.travelAt(loading_->time(*lmp_) - loading_->state().startTime)
    );
    std::vector<double> columns{buoyancy, submerged, share, platenBuoyancy};
    if (externalWater_)
    {
        const std::vector<double> own = externalWater_->values();
        columns.insert(columns.end(), own.begin(), own.end());
    }
    columns.push_back(settings_.endSupport->reaction(context_.comm()));
    const std::vector<double> own = test_->curveValues(*bonds_, context_.comm(), layerFirstTag_);
    columns.insert(columns.end(), own.begin(), own.end());
    return columns;
}


void RidgeScene::advance(long steps)
{
    if (!externalWater_)
    {
        lmp_->command("run " + std::to_string(steps) + " pre no post no");
        return;
    }
    const long chunk = externalWater_->stepsPerAdvance;
    externalWater_->advance((steps + chunk - 1) / chunk * chunk);
}


Provenance RidgeScene::assemblyInputs(const Provenance& made) const
{
    Provenance p;
    p.add("stage", "ridgeDEM assemble");
    const std::string keel = "keel (settledRubble)";
    if (!settings_.hasKeel)
    {
        p.add(keel, "none");
    }
    else if (std::filesystem::exists(settings_.keelFile) || made.empty())
    {
        p.addFileContent(keel, settings_.keelFile);
    }
    else
    {
        context_.log("Note: the keel " + settings_.keelFile + " is gone; DEM/ridge.h5's other inputs are checked");
        p.add(keel, made.value(keel));
    }
    p.addDictionaryFile("constant/iceProperties", context_.path("constant/iceProperties"));
    p.addDictionaryFile("constant/freezeBondProperties", context_.path("constant/freezeBondProperties"));
    // Not the test's entries, nor how the ends are held in it (the pads'
    // length, fixedLength, is the assembly's: it types their particles).
    const Dictionary ridgeProperties = Dictionary::readFile(context_.path("constant/ridgeProperties"));
    p.addDictionary("constant/ridgeProperties", ridgeProperties, {"test", "ends"});
    p.addDictionary("constant/ridgeProperties", ridgeProperties.subDict("ends"), {"endSupport", "floatingCoeffs"});
    const Dictionary coupling = Dictionary::readFile(context_.path("constant/couplingProperties"));
    if (coupling.isDict("hydrostatic"))
    {
        // The assembly is in still water at every level.
        p.addDictionary("constant/couplingProperties", coupling.subDict("hydrostatic"));
    }
    if (std::filesystem::exists(context_.path("constant/g")))
    {
        p.addDictionaryFile("constant/g", context_.path("constant/g"));
    }
    p.addFileContent("DEM/in.ridge", context_.path("DEM/in.ridge"));
    return p;
}


Provenance RidgeScene::loadingInputs(const Provenance& ridge) const
{
    Provenance p;
    p.add("stage", context_.application() + " load");
    p.addStage("DEM/ridge.h5", ridge);
    const Dictionary ridgeProperties = Dictionary::readFile(context_.path("constant/ridgeProperties"));
    p.addDictionary("constant/ridgeProperties", ridgeProperties.subDict("test"),
                    {"referenceFlexuralStrength"});
    p.addDictionary("constant/ridgeProperties", ridgeProperties.subDict("ends"));
    p.addDictionaryFile("constant/couplingProperties", context_.path("constant/couplingProperties"));
    p.addDictionaryFile(settings_.controlFile, context_.path(settings_.controlFile),
                        {"writeInterval", "checkpointInterval", "vtkFormat"});
    return p;
}


void RidgeScene::load()
{
    const auto wallStart = std::chrono::steady_clock::now();
    if (!std::filesystem::exists(context_.path("DEM/ridge.h5")))
    {
        throw InputError(context_.path("DEM/ridge.h5"), "(file)", "missing: run the assemble stage first (-stage assemble)");
    }
    const SavedRubble ridge = SavedRubble::read(context_.path("DEM/ridge.h5"), SavedRubble::ridge);
    const Provenance ridgeInputs = Provenance::fromText(ridge.provenance);
    requireSameInputs(ridgeInputs, assemblyInputs(ridgeInputs), context_.path("DEM/ridge.h5"),
        "ridgeDEM -case " + settings_.caseDir + " -stage assemble");
    int maxBlock = -1;
    for (const SavedParticle& p : ridge.particles) maxBlock = std::max(maxBlock, p.block);
    const int layerBlock = settings_.layer.thickness > 0.0 ? maxBlock : -1;
    RidgeGeometry geometry = measureRidge(ridge.particles, layerBlock, settings_.layer.length, settings_.layer.width);
    geometry.waterLevel = ridge.waterLevel;
    if (context_.rank() == 0)
    {
        writeGeometry(geometry, ridge.particles);
    }
    layerFirstTag_ = geometry.keelParticles + 1;
    // The freeze-bonds' strengths as assembled, for the summary.
    freezeBondCount_ = 0;
    double sumTensile = 0.0, sumShear = 0.0;
    for (const BondState& b : ridge.bonds)
    {
        if (b.family != BondFamily::freeze) continue;
        ++freezeBondCount_;
        sumTensile += b.tensileStrength;
        sumShear += b.shearStrength;
    }
    freezeParticleStrength_ = freezeBondCount_ > 0
        ? BondStrengthPair{sumTensile/freezeBondCount_, sumShear/freezeBondCount_} : BondStrengthPair{};

    std::vector<ParticleSpec> particles(ridge.particles.size());
    std::vector<int> types(ridge.particles.size());
    double topUnderPlaten = -HUGE_VAL;
    const double xLoad = 0.5 * settings_.layer.length;
    for (std::size_t k = 0; k < particles.size(); ++k)
    {
        const SavedParticle& s = ridge.particles[k];
        particles[k].position = s.position;
        particles[k].radius = s.radius;
        particles[k].block = s.block;
        types[k] = test_->particleType(s.type, static_cast<long>(k) >= geometry.keelParticles);
        // The end pads were saved fixed; simple and floating supports free them.
        if (s.type == fixedType && types[k] == fixedType && settings_.endSupport->padsIntegrated())
        {
            types[k] = mobileType;
        }
        if (std::abs(s.position.x() - xLoad) < 0.5 * settings_.platenLength + s.radius)
        {
            topUnderPlaten = std::max(topUnderPlaten, s.position.z() + s.radius);
        }
    }
    // The ridge settles with the true inertia (a settling is no quasi-static
    // loading: its motion is the answer), then loads with the scaled one.
    chooseContactsAndStep(particles, ice_);
    const double settleDt = dt_;
    const double inertiaScaling = settings_.loading.inertiaScaling;
    if (inertiaScaling != 1.0)
    {
        chooseContactsAndStep(particles, ice_, inertiaScaling);
    }

    // The end support's view of the ridge: the platen pushes down (-z), the
    // pads are the particles saved fixed at each end, their inner faces at
    // fixedLength from the ends.
    ends_.loadAxis = 2;
    ends_.pushSign = -1;
    ends_.supportX[0] = settings_.fixedEndLength;
    ends_.supportX[1] = settings_.layer.length - settings_.fixedEndLength;
    ends_.rollerDiameter = 0.1;     // as the three-point bending test's supports (assumed)
    ends_.contactStiffness = contact_.normalStiffness;
    ends_.contactDamping = contact_.normalDamping;
    ends_.bodyLo = Vec3(0.0, 0.0, geometry.keelBottom);
    ends_.bodyHi = Vec3(settings_.layer.length, settings_.layer.width, geometry.clTop);
    ends_.density = ice_.material.density;
    ends_.particles = particles;
    ends_.endOfTag.assign(particles.size(), -1);
    if (!test_->needsLayer())   // the keel-bond tests hold the whole keel
    {
        for (std::size_t k = 0; k < particles.size(); ++k)
        {
            if (ridge.particles[k].type == fixedType)
            {
                ends_.endOfTag[k] = particles[k].position.x() < 0.5 * settings_.layer.length ? 0 : 1;
            }
        }
    }
    std::vector<std::string> extraColumnNames{"buoyancy", "submergedVolume", "buoyancyShare", "platenBuoyancy"};
    if (externalWater_)
    {
        if (settings_.resume)
        {
            throw InputError("command line", "-resume", "a checkpoint holds the DEM only, not the "
                + externalWater_->name + " water: a run at that level starts again");
        }
        extraColumnNames.insert(extraColumnNames.end(), externalWater_->columns.begin(), externalWater_->columns.end());
    }
    extraColumnNames.push_back("supportReaction");  // the end support's, along z, averaged since the last sample
    for (const std::string& name : test_->curveColumns())
    {
        extraColumnNames.push_back(name);
    }
    loading_ = std::make_unique<PlatenLoading>
    (
        context_, settings_.loading, dt_,
        particleCount_, fixedType, extraColumnNames
    );
    loading_->measureWallFrom(wallStart);
    loading_->setInputs(loadingInputs(ridgeInputs));
    loading_->setTimeStepChangedAtStart(settleDt != dt_);
    loading_->setMotionPrescribed(!test_->integratesParticles());
    std::unique_ptr<Checkpoint> checkpoint;
    if (settings_.resume && loading_->checkpointExists())
    {
        checkpoint = std::make_unique<Checkpoint>(loading_->readCheckpoint());
    }
    startLiggghts
    (
        particles, types, ice_,
        checkpoint ? "read_restart " + loading_->restartFile(*checkpoint) : "read_data " + context_.path("DEM/ridge.data"),
        checkpoint ? dt_ : settleDt
    );
    if (!test_->integratesParticles())
    {
        lmp_->command("unfix integrate");
    }

    test_->defineFixes(*lmp_, context_, topUnderPlaten);
    if (externalWater_)
    {
        HydrostaticWaterParameters surface;
        surface.surfaceLevel = ridge.waterLevel;
        surface.density = externalWater_->density;
        surface.gravity = water_.gravity.norm();
        stillSurface_ = std::make_unique<HydrostaticWater>(surface);
        externalWater_->defineForceFix(*lmp_, ridge.waterLevel);
    }
    else
    {
        HydrostaticWaterParameters waterParameters = water_.hydrostatic;
        waterParameters.surfaceLevel = ridge.waterLevel;
        waterForces_ = std::make_unique<WaterForces>(*lmp_, HydrostaticWater(waterParameters));
        waterForces_->defineForceFix();
    }
    EndSupport& support = *settings_.endSupport;
    support.defineForces(*lmp_, context_, ends_);
    bonds_ = IceBondForces::define(*lmp_, ice_);
    support.defineMotion(*lmp_, ends_);
    context_.log("End support " + support.description());
    if (test_->integratesParticles() && waterForces_)
    {
        // Not in the keel-bond tests: nothing is integrated there, and the fix
        // would scale the layer's forces that testForce() sums by m / (m + m_a).
        waterForces_->defineAddedMassFix();
    }
    lmp_->command("run 0");     // property/atom is reset by the first run's set-up
    if (checkpoint)
    {
        loading_->resumeFrom(*checkpoint, *lmp_, *bonds_);
    }
    else
    {
        bonds_->restoreBonds(ridge.bonds);
    }
    lmp_->command("run 0");

    const long settleSteps = test_->settlesFirst() ? std::lround(settings_.settleTime / settleDt) : 0;
    if (!checkpoint && settleSteps > 0)
    {
        // The bonds were made at the pressed geometry with no load in them:
        // the ridge first finds its equilibrium under gravity and buoyancy.
        // Nor is switching from the soft assembly contacts to the ice contacts
        // a load: no bond breaks meanwhile; one overloaded at rest breaks at
        // the first step of the test.
        bonds_->suspendBreakage(true);
        advance(settleSteps);
        bonds_->suspendBreakage(false);
        context_.log("Settled under gravity and buoyancy for " + formatNumber(settings_.settleTime) + " s: kinetic energy "
            + formatNumber(totalKineticEnergy(*lmp_)) + " J");
    }
    if (!checkpoint && dt_ != settleDt)
    {
        // LIGGGHTS' clock keeps the settling's time and counts on with this step.
        lmp_->command("timestep " + exactNumber(dt_));
    }
    // The test moves off smoothly (loading.rampTravel): a sudden start would
    // hit the ice with a force spike.
    const long startStep = checkpoint ? checkpoint->state.liggghtsStepAtStart : lmp_->step();
    const std::string speed = settings_.loading.speedFormula(startStep, dt_);
    const std::string travel = settings_.loading.travelFormula(startStep, dt_);
    lmp_->command("variable zero equal 0");
    test_->startMotion(*lmp_, speed, travel);
    if (inertiaScaling != 1.0)
    {
        // The last force fix: after the water's added mass, with which it multiplies.
        inertia_ = std::make_unique<InertiaScalingFix>(*lmp_, inertiaScaling);
        inertia_->define();
    }
    // The loading runs skip LIGGGHTS' set-up (pre no); a moving mesh is only
    // registered as moving by one, so the motion gets its own.
    lmp_->command("run 0 post no");

    std::ostringstream msg;
    msg << "Loading: " << particleCount_ << " particles (" << geometry.keelParticles << " keel, "
        << geometry.layerParticles << " layer), " << ridge.bonds.size() << " bonds, depth "
        << geometry.depth() << " m, water surface " << ridge.waterLevel << " m, time step " << dt_ << " s";
    if (inertiaScaling != 1.0)
    {
        msg << " (inertia scaled by " << inertiaScaling << "; settled with the true inertia at " << settleDt << " s)";
    }
    context_.log(msg.str());

    PlatenLoading::Hooks hooks;
    hooks.force = [this] { return testForce(); };
    hooks.extras = [this] { return extraColumns(); };
    hooks.stopEjecta = [this] { return stopParticlesAtBoxEdge(); };
    hooks.failure = [this]
    {
        std::string f = waterForces_ ? waterForces_->failure() : std::string();
        return f.empty() && inertia_ ? inertia_->failure() : f;
    };
    if (externalWater_)
    {
        hooks.advance = externalWater_->advance;
        hooks.stepsPerAdvance = externalWater_->stepsPerAdvance;
    }
    loading_->run(*lmp_, *bonds_, hooks, [&] { writeSummary(geometry); });
    loading_->logEnd();
}


void RidgeScene::writeSummary(const RidgeGeometry& g) const
{
    if (context_.rank() != 0)
    {
        return;
    }
    const CsvWriter& curve = loading_->curve();
    const BreakageRecord& breaks = loading_->breakage();
    const std::size_t rows = curve.nRows();
    double peak = -HUGE_VAL, travelAtPeak = 0.0, shareAtPeak = 0.0, reactionAtPeak = 0.0;
    const double startForce = rows > 0 ? curve.row(0)[PlatenLoading::forceColumn] : 0.0;
    if (rows > 0)
    {
        const std::vector<double>& row = curve.row(curve.rowOfLargest(PlatenLoading::forceColumn));
        peak = row[PlatenLoading::forceColumn];
        travelAtPeak = row[PlatenLoading::travelColumn];
        shareAtPeak = row[curve.columnIndex("buoyancyShare")];
        reactionAtPeak = row[curve.columnIndex("supportReaction")];
    }
    // Freeze-bonds broken in tension, and those between layer and keel.
    std::size_t freezeBroken = 0, freezeTension = 0, interfaceBroken = 0;
    for (const BreakEvent& e : breaks.events())
    {
        if (e.family != BondFamily::freeze) continue;
        ++freezeBroken;
        freezeTension += e.mode == BreakMode::tension;
        interfaceBroken += (e.tagA >= layerFirstTag_) != (e.tagB >= layerFirstTag_);
    }

    Json byMode;
    byMode["tension"] = long(breaks.count(BreakMode::tension));
    byMode["shear"] = long(breaks.count(BreakMode::shear));
    byMode["twist"] = long(breaks.count(BreakMode::twist));
    byMode["bending"] = long(breaks.count(BreakMode::bending));
    Json byFamily;
    byFamily["ice"] = long(breaks.count(BondFamily::ice));
    byFamily["freeze"] = long(freezeBroken);

    Json j;
    j["case"] = "ridge";
    j["complete"] = true;
    j["test"] = settings_.test;
    j["water"] = externalWater_ ? externalWater_->name : toString(water_.level);
    j["consolidated_layer_m"] = settings_.layer.thickness;
    j["keel_thickness_m"] = g.keelTop - g.keelBottom;
    j["depth_m"] = g.depth();
    j["water_level_m"] = g.waterLevel;
    j["freeze_bond_set"] = freezeBondProperties_.summary();
    j["end_support"] = settings_.endSupport->summary();
    j["support_reaction_at_peak_N"] = reactionAtPeak;
    // The freeze-bonds of DEM/ridge.h5: the particle-level strengths they break at
    // (means), the effective ones the set asks for (c_f times the real strengths,
    // on the bond area; a fixed set's are the same for every bond) and, when
    // calibrated, what the virtual tests give with the particle strengths.
    const FreezeBondParticleStrength& particleStrength = freezeBondProperties_.particleStrength();
    j["freeze_bonds"] = freezeBondCount_;
    j["freeze_bond_particle_strengths"] = particleStrength.name();
    if (dynamic_cast<const FixedSetStrength*>(&freezeBondProperties_.strengthModel()))
    {
        const FreezeBondStrength set = freezeBondProperties_.strength(0.0, 1.0);
        j["freeze_bond_effective_tensile_Pa"] = set.effectiveTensile;
        j["freeze_bond_effective_shear_Pa"] = set.effectiveShear;
    }
    j["freeze_bond_particle_tensile_mean_Pa"] = freezeParticleStrength_.tensile;
    j["freeze_bond_particle_shear_mean_Pa"] = freezeParticleStrength_.shear;
    if (particleStrength.name() != "direct")
    {
        const BondStrengthPair virtualTests = particleStrength.effective(freezeParticleStrength_);
        j["freeze_bond_virtual_test_tensile_Pa"] = virtualTests.tensile;
        j["freeze_bond_virtual_test_shear_Pa"] = virtualTests.shear;
    }
    j["peak_force_N"] = peak;
    j["travel_at_peak_m"] = travelAtPeak;
    j["force_at_start_N"] = startForce;
    j["buoyancy_share_at_peak_N"] = shareAtPeak;
    j["peak_force_without_buoyancy_N"] = peak - shareAtPeak;
    test_->addFigures(j, g, curve, peak, startForce);
    j["broken_bonds"] = long(breaks.size());
    j["broken_by_mode"] = byMode;
    j["broken_by_family"] = byFamily;
    j["freeze_bonds_broken_in_tension_share"] = freezeBroken > 0 ? double(freezeTension) / freezeBroken : 0.0;
    j["layer_keel_bonds_broken"] = long(interfaceBroken);
    j["particles"] = particleCount_;
    j["keel_particles"] = g.keelParticles;
    j["layer_particles"] = g.layerParticles;
    j["platen_speed_m_per_s"] = settings_.loading.speed;
    j["ejected_particles_stopped"] = long(loading_->state().frozenEjecta);
    loading_->addQuasiStaticFigures(j);
    j["steps"] = loading_->state().steps;
    j["dt"] = dt_;
    j["ranks"] = context_.ranks();
    j["inputs_fingerprint"] = loading_->inputs().fingerprint();
    loading_->addRunCostFigures(j);
    writeFileAtomically(context_.path("postProcessing/summary.json"), jsonText(j));
}

} // namespace iceDEM
