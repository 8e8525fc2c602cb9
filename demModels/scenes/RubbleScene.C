#include "RubbleScene.H"
#include "CommandLine.H"
#include "CompactionPlateLaw.H"
#include "CompactionPlates.H"
#include "NamedEnum.H"

#include "Percentile.H"

#include "AtomicFile.H"
#include "BondBuilder.H"
#include "BondModel.H"
#include "CsvWriter.H"
#include "Dictionary.H"
#include "InertiaScaling.H"
#include "HydrostaticWater.H"
#include "IceBondForces.H"
#include "FreezeBonding.H"
#include "HeatBalanceAreaCorrection.H"
#include "InterfaceAreaCorrection.H"
#include "InputError.H"
#include "Format.H"
#include "Json.H"
#include "LiggghtsInstance.H"
#include "ParticleGather.H"
#include "SceneSetup.H"
#include "TimeStep.H"
#include "VtkWriter.H"
#include "WaterForces.H"

#include "atom.h"
#include "update.h"
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
constexpr int wallType = 3;

const NamedEnum<CompactionMethod> compactionMethodNames
{{
    {CompactionMethod::plates, "plates"},
    {CompactionMethod::none, "none"},
}};


//- The settled layer's figures (settling.json and summary.json alike).
void addSettledLayer(Json& j, const SettledLayer& layer)
{
    j["settled_time_s"] = layer.time;
    j["at_rest"] = layer.atRest;
    j["kinetic_energy_per_particle_J"] = layer.kineticEnergyPerParticle;
    j["layer_bottom_m"] = layer.bottom;
    j["layer_top_m"] = layer.top;
    j["thickness_m"] = layer.thickness;
    j["porosity"] = layer.porosity;
    j["sphere_porosity"] = layer.spherePorosity;
    j["ice_volume_above_water_fraction"] = layer.volumeAboveWater;
    j["freeboard_m"] = layer.freeboard;
}

} // namespace


RubbleSettings RubbleSettings::read(int argc, char** argv)
{
    RubbleSettings s;
    std::string shapeOverride;
    CommandLine("rubbleDEM")
        .text("-case", "DIR", "the case directory (default .)", s.caseDir)
        .choice("-stage", {"settle", "compact", "bond", "all"}, "which stage to run (default all)", s.stage)
        .choice("-shape", {"cuboid", "empirical"}, "block shape instead of blocks.shape", shapeOverride)
        .flag("-resume", "settle: continue from the last checkpoint", s.resume)
        .parse(argc, argv);
    RubbleSettings fromCase = readCase(s.caseDir, s.stage, shapeOverride);
    fromCase.resume = s.resume;
    return fromCase;
}


RubbleSettings RubbleSettings::readCase(const std::string& caseDir, const std::string& stage,
                                        const std::string& shapeOverride)
{
    RubbleSettings s;
    s.caseDir = caseDir;
    s.stage = stage;
    const std::string file = s.caseDir + "/constant/rubbleProperties";
    const Dictionary d = Dictionary::readFile(file);
    d.checkKeys({"box", "blocks", "settling", "compaction", "ends", "inertiaScaling"});
    refuseInertiaScaling(d, "inertiaScaling",
        "rubble settling is no quasi-static loading: how the blocks fall, tilt and come to rest under gravity and "
        "buoyancy is the answer, and with the inertia scaled every motion is sqrt(s) times slower (the keel would "
        "settle later or differently, and the stop rule on the kinetic energy would mean another thing)");
    const Dictionary& box = d.subDict("box");
    box.checkKeys({"length", "width", "height"});
    s.boxLength = box.getPositiveScalarOrDefault("length", s.boxLength);
    s.boxWidth = box.getPositiveScalarOrDefault("width", s.boxWidth);
    s.boxHeight = box.getPositiveScalarOrDefault("height", s.boxHeight);

    const Dictionary& b = d.subDict("blocks");
    b.checkKeys({"shape", "sizes", "syntheticCoeffs", "particleDiameter", "layers", "rubbleThickness",
                 "expectedPorosity", "seed"});
    s.shape = shapeOverride.empty()
        ? blockShapeFromName(b.getWord("shape"), file, b.entryPath("shape"))
        : blockShapeFromName(shapeOverride, "command line", "-shape");
    const std::string sizes = b.getString("sizes");
    if (sizes != "synthetic")
    {
        s.sizesFile = sizes.front() == '/' ? sizes : s.caseDir + "/" + sizes;
    }
    if (b.found("syntheticCoeffs"))
    {
        const Dictionary& c = b.subDict("syntheticCoeffs");
        c.checkKeys({"minWidth", "maxWidth", "minAspect", "maxAspect", "minAreaFraction", "maxAreaFraction"});
        auto& p = s.synthetic;
        p.minWidth = c.getPositiveScalarOrDefault("minWidth", p.minWidth);
        p.maxWidth = c.getPositiveScalarOrDefault("maxWidth", p.maxWidth);
        p.minAspect = c.getPositiveScalarOrDefault("minAspect", p.minAspect);
        p.maxAspect = c.getPositiveScalarOrDefault("maxAspect", p.maxAspect);
        p.minAreaFraction = c.getPositiveScalarOrDefault("minAreaFraction", p.minAreaFraction);
        p.maxAreaFraction = c.getPositiveScalarOrDefault("maxAreaFraction", p.maxAreaFraction);
        if (p.maxWidth < p.minWidth) c.fail("maxWidth", "must be at least minWidth");
        if (p.minAspect < 1.0 || p.maxAspect < p.minAspect) c.fail("maxAspect", "need 1 <= minAspect <= maxAspect");
        if (p.maxAreaFraction > 1.0 || p.maxAreaFraction < p.minAreaFraction)
            c.fail("maxAreaFraction", "need 0 < minAreaFraction <= maxAreaFraction <= 1");
    }
    s.particleDiameter = b.getPositiveScalarOrDefault("particleDiameter", s.particleDiameter);
    s.layers = b.getLabelOrDefault("layers", s.layers);
    if (s.layers < 1) b.fail("layers", "must be at least 1");
    s.rubbleThickness = b.getPositiveScalarOrDefault("rubbleThickness", s.rubbleThickness);
    const Dictionary& c = d.subDict("compaction");
    c.checkKeys({"method", "targetPorosity", "speed", "maxPressure", "frictionCoefficient", "youngsModulus", "holdTime",
                  "holdPressure", "releaseTime"});
    s.compaction = compactionMethodNames.get(c, "method");
    if (s.compaction == CompactionMethod::plates)
    {
        s.targetPorosity = c.getScalar("targetPorosity");
        if (!(s.targetPorosity >= 0.1 && s.targetPorosity < 0.9)) c.fail("targetPorosity", "must lie in [0.1, 0.9)");
        s.compactionSpeed = c.getPositiveScalarOrDefault("speed", s.compactionSpeed);
        s.maxCompactionPressure = c.getPositiveScalarOrDefault("maxPressure", s.maxCompactionPressure);
        if (c.found("frictionCoefficient"))
        {
            s.compactionFriction = c.getScalar("frictionCoefficient");
            if (!(s.compactionFriction >= 0.0)) c.fail("frictionCoefficient", "must not be negative");
        }
        if (c.found("youngsModulus"))
        {
            s.compactionYoungsModulus = c.getScalar("youngsModulus");
            if (!(s.compactionYoungsModulus > 0.0)) c.fail("youngsModulus", "must be positive (Pa)");
        }
        s.holdTime = c.getScalarOrDefault("holdTime", s.holdTime);
        if (!(s.holdTime >= 0.0)) c.fail("holdTime", "must not be negative");
        s.holdPressure = c.getScalarOrDefault("holdPressure", s.holdPressure);
        if (!(s.holdPressure >= 0.0 && s.holdPressure < s.maxCompactionPressure))
        {
            c.fail("holdPressure", "must lie in [0, maxPressure)");
        }
        s.releaseTime = c.getScalarOrDefault("releaseTime", s.releaseTime);
        if (!(s.releaseTime >= 0.0)) c.fail("releaseTime", "must not be negative");
        if (b.found("expectedPorosity"))
        {
            b.fail("expectedPorosity", "is for uncompacted rubble (compaction.method none): with plates the ice "
                "rained in is that of a rubbleThickness layer at compaction.targetPorosity; remove this entry");
        }
        s.expectedPorosity = s.targetPorosity;
    }
    else
    {
        if (s.stage == "compact")
        {
            c.fail("method", "is none: there is no compact stage to run (plates compacts)");
        }
        s.expectedPorosity = b.getScalar("expectedPorosity");
        if (!(s.expectedPorosity >= 0.0 && s.expectedPorosity < 0.9)) b.fail("expectedPorosity", "must lie in [0, 0.9)");
    }
    s.seed = static_cast<unsigned>(b.getLabelOrDefault("seed", static_cast<int>(s.seed)));

    const Dictionary& st = d.subDict("settling");
    st.checkKeys({"youngsModulus", "dampingAlpha", "maxTime", "minTime", "kineticEnergyThreshold",
                  "checkInterval", "checkpointInterval", "sheetGap", "firstSheetClearance", "maxTilt",
                  "frictionCoefficient"});
    s.settlingYoungsModulus = st.getPositiveScalarOrDefault("youngsModulus", s.settlingYoungsModulus);
    s.settlingDampingAlpha = st.getScalarOrDefault("dampingAlpha", s.settlingDampingAlpha);
    if (!(s.settlingDampingAlpha >= 0.0 && s.settlingDampingAlpha < 1.0)) st.fail("dampingAlpha", "must lie in [0, 1)");
    if (st.found("frictionCoefficient"))
    {
        s.settlingFriction = st.getScalar("frictionCoefficient");
        if (!(s.settlingFriction >= 0.0)) st.fail("frictionCoefficient", "must not be negative");
    }
    s.maxTime = st.getPositiveScalarOrDefault("maxTime", s.maxTime);
    s.minTime = st.getScalarOrDefault("minTime", s.minTime);
    s.kineticEnergyThreshold = st.getPositiveScalarOrDefault("kineticEnergyThreshold", s.kineticEnergyThreshold);
    s.checkInterval = st.getPositiveScalarOrDefault("checkInterval", s.checkInterval);
    s.checkpointInterval = st.getPositiveScalarOrDefault("checkpointInterval", s.checkpointInterval);
    s.sheetGap = st.getPositiveScalarOrDefault("sheetGap", s.sheetGap);
    s.firstSheetClearance = st.getScalarOrDefault("firstSheetClearance", s.firstSheetClearance);
    s.maxTilt = st.getScalarOrDefault("maxTilt", s.maxTilt);
    if (!(s.maxTilt >= 0.0 && s.maxTilt <= 90.0)) st.fail("maxTilt", "must lie in [0, 90] degrees");

    const Dictionary& e = d.subDict("ends");
    e.checkKeys({"fixedLength"});
    s.fixedEndLength = e.getScalarOrDefault("fixedLength", s.fixedEndLength);
    if (!(s.fixedEndLength >= 0.0 && 2*s.fixedEndLength < s.boxLength)) e.fail("fixedLength", "must lie in [0, length/2)");

    // The case's output entry, in the controlDict of the case that loads the rubble later
    // (the other entries there are that application's).
    const std::string control = s.caseDir + "/system/controlDict";
    if (std::filesystem::exists(control))
    {
        s.vtkFormat = readVtkFormat(Dictionary::readFile(control));
    }
    return s;
}


RubbleScene::RubbleScene(MPI_Comm comm, const RubbleSettings& settings, const ExternalWater* externalWater)
:
    context_(comm, settings.caseDir, externalWater ? "iceRubbleFoam" : "rubbleDEM"),
    settings_(settings),
    externalWater_(externalWater)
{
    ice_ = IceProperties::read(context_.path("constant/iceProperties"));
    requireFreezeBondStrengthsPerBond(ice_, context_.path("constant/iceProperties"));
    freezeBondProperties_ = FreezeBondProperties::read(context_.path("constant/freezeBondProperties"));
    freezeBondProperties_.checkIce(ice_, context_.path("constant/iceProperties"));
    if (dynamic_cast<const InterfaceAreaCorrection*>(&freezeBondProperties_.areaCorrection()))
    {
        throw InputError(context_.path("constant/freezeBondProperties"), "areaCorrection.model",
            "interface is for laboratory specimens; rubble needs given or heatBalance");
    }
    water_ = WaterProperties::readCase(settings_.caseDir);
    const std::string coupling = context_.path("constant/couplingProperties");
    if (externalWater_ && (water_.level != WaterLevel::cfd || settings_.stage != "settle"))
    {
        throw InputError(coupling, "waterLevel", "'" + toString(water_.level) + "', stage " + settings_.stage
            + ": iceRubbleFoam settles the rubble at the cfd level (stage settle, waterLevel cfd); "
            "the other stages and levels run in rubbleDEM");
    }
    if (externalWater_ && settings_.resume)
    {
        throw InputError("command line", "-resume", "a settling checkpoint holds the DEM only, not the "
            + externalWater_->name + " water: a settling at that level starts again");
    }
    const bool settles = settings_.stage == "settle" || settings_.stage == "all";
    if (water_.level == WaterLevel::vof)
    {
        throw InputError(coupling, "waterLevel", "vof: the moving free surface is built for the ridge scenes' "
            "loading (icePunchInterFoam) only; the rubble settles at none, hydrostatic (rubbleDEM) or cfd "
            "(iceRubbleFoam)");
    }
    if (!externalWater_ && water_.level == WaterLevel::cfd && settles)
    {
        throw InputError(coupling, "waterLevel", "cfd: rubbleDEM settles in still (hydrostatic) water; the "
            "settling at the cfd level runs in iceRubbleFoam (cases/rubbleBeam: ./Allrun -water cfd), and "
            "rubbleDEM then compacts and bonds it (-stage compact, -stage bond)");
    }
    if (water_.level == WaterLevel::cfd && water_.hydrostatic.surfaceLevel <= 0.0)
    {
        throw InputError(coupling, "hydrostatic", "at the cfd level the blocks are rained towards the still "
            "surface, and compacted and bonded in still water: needs hydrostatic { surfaceLevel; rho; mu; } "
            "(the fluid mesh ends at surfaceLevel)");
    }
    // Raining only has to produce the settled geometry: softer contacts and
    // bonds (a longer time step), unbreakable blocks and more damping.
    settlingIce_ = ice_.softenedForAssembly(settings_.settlingYoungsModulus, settings_.settlingDampingAlpha);
    if (settings_.settlingFriction >= 0.0)
    {
        settlingIce_.material.frictionCoefficient = settings_.settlingFriction;
    }
    // Contacts as soft as the settling's hold the compaction's pressure as
    // overlaps (millimetres between 55 mm spheres) that spring back when the
    // lid backs off; near the ice's stiffness the blocks must rearrange instead.
    compactionIce_ = settlingIce_;
    if (settings_.compactionYoungsModulus > 0.0)
    {
        compactionIce_ = ice_.softenedForAssembly(settings_.compactionYoungsModulus, settings_.settlingDampingAlpha);
        compactionIce_.material.frictionCoefficient = settlingIce_.material.frictionCoefficient;
    }
}


RubbleScene::~RubbleScene() = default;




void RubbleScene::buildBlocks()
{
    RubbleSpec spec;
    spec.boxLength = settings_.boxLength;
    spec.boxWidth = settings_.boxWidth;
    spec.particleDiameter = settings_.particleDiameter;
    spec.layers = settings_.layers;
    spec.shape = settings_.shape;
    spec.iceVolume = (1.0 - settings_.expectedPorosity)*settings_.boxLength*settings_.boxWidth*settings_.rubbleThickness;
    spec.firstSheetBase =
        (water_.level == WaterLevel::none ? 0.0 : water_.hydrostatic.surfaceLevel) + settings_.firstSheetClearance;
    spec.sheetGap = settings_.sheetGap;
    spec.maxTilt = settings_.maxTilt*M_PI/180.0;
    spec.seed = settings_.seed;
    const BlockSizeSource sizes = settings_.sizesFile.empty()
        ? BlockSizeSource::synthetic(settings_.synthetic)
        : BlockSizeSource::fromCsv(settings_.sizesFile);
    rubble_ = buildRubble(spec, sizes);
    blockOfTag_.clear();
    for (const ParticleSpec& p : rubble_.particles)
    {
        blockOfTag_.push_back(p.block);
    }
    std::ostringstream msg;
    msg << "Blocks: " << rubble_.blocks.size() << " " << name(settings_.shape) << " blocks ("
        << (settings_.sizesFile.empty() ? "synthetic sizes" : settings_.sizesFile) << "), "
        << rubble_.particles.size() << " particles of " << settings_.particleDiameter*1e3 << " mm, "
        << rubble_.iceVolume << " m3 of ice, block thickness " << rubble_.blockThickness << " m";
    context_.log(msg.str());
}


void RubbleScene::startLiggghts(const SavedRubble* from, const IceProperties& stageIce, const std::string& restart,
                                bool withPlates)
{
    const IceProperties& ice = stageIce;
    const double r = 0.5*settings_.particleDiameter;
    const double mass = ice.material.density*4.0/3.0*M_PI*r*r*r;
    stageContact_ = ContactParameters::of(ice, settings_.particleDiameter, mass);
    stageYoungsModulus_ = ice.material.youngsModulus;
    const ContactParameters& contact = stageContact_;

    std::vector<ParticleSpec> particles = rubble_.particles;
    std::vector<int> types(particles.size(), mobileType);
    if (from)
    {
        particles.resize(from->particles.size());
        types.resize(from->particles.size());
        blockOfTag_.resize(from->particles.size());
        for (std::size_t k = 0; k < particles.size(); ++k)
        {
            particles[k].position = from->particles[k].position;
            particles[k].radius = from->particles[k].radius;
            particles[k].block = blockOfTag_[k] = from->particles[k].block;
            types[k] = from->particles[k].type;
        }
    }
    double top = 0.0;
    for (const ParticleSpec& p : particles) top = std::max(top, p.position.z());
    if (context_.rank() == 0)
    {
        std::filesystem::create_directories(context_.path("DEM"));
        writeLiggghtsData
        (
            context_.path("DEM/rubble.data"), "rubble written by rubbleDEM", particles, ice.material.density,
            Vec3(-0.05, -0.05, -0.05), Vec3(settings_.boxLength + 0.05, settings_.boxWidth + 0.05, top + 0.5),
            3, [&](const ParticleSpec& p) { return types[&p - particles.data()]; }
        );
    }
    MPI_Barrier(context_.comm());

    // Time step from the ice bonds and contacts of the close packing (12 neighbours at most).
    const TimeStepLimits limits = timeStepLimits(ice, r, 12);
    dt_ = chooseTimeStep(ice, limits, context_.path("constant/iceProperties"));

    const double skin = 0.2*r;
    ScriptVariables variables
    {
        {"readParticles", "\"" + (restart.empty() ? "read_data " + context_.path("DEM/rubble.data")
                                                    : "read_restart " + restart) + "\""},
        {"ghostCutoff", exactNumber(bondGhostCutoff(ice, r, skin))},
        {"neighbourSkin", exactNumber(skin)},
        {"dt", exactNumber(dt_)},
        {"gravity", exactNumber(water_.gravity.norm())},
        {"boxLength", exactNumber(settings_.boxLength)},
        {"boxWidth", exactNumber(settings_.boxWidth)}
    };
    const ScriptVariables contacts = boxContactVariables(contact);
    variables.insert(variables.end(), contacts.begin(), contacts.end());
    lmp_ = context_.startLiggghts(variables, "DEM/in.rubbleBeam");

    if (from && restart.empty())
    {
        LAMMPS_NS::Atom& atom = *lmp_->engine().atom;
        for (int i = 0; i < atom.nlocal; ++i)
        {
            const SavedParticle& p = from->particles.at(atom.tag[i] - 1);
            for (int k = 0; k < 3; ++k)
            {
                atom.v[i][k] = p.velocity[k];
                atom.omega[i][k] = p.angularVelocity[k];
            }
        }
    }

    waterForces_.reset();
    if (externalWater_)
    {
        externalWater_->defineForceFix(*lmp_, water_.hydrostatic.surfaceLevel);
    }
    else if (water_.level != WaterLevel::none)
    {
        // hydrostatic, or the stages after a settling at the cfd level
        waterForces_ = std::make_unique<WaterForces>(*lmp_, HydrostaticWater(water_.hydrostatic));
        waterForces_->defineForceFix();
    }
    plates_.reset();
    if (withPlates)
    {
        plates_ = std::make_unique<CompactionPlates>
        (
            *lmp_, CompactionPlateLaw{contact.normalStiffness, contact.normalDamping}
        );
        plates_->define();
    }
    bonds_ = IceBondForces::define(*lmp_, ice);
    if (waterForces_)
    {
        waterForces_->defineAddedMassFix();
    }
    lmp_->command("run 0");     // property/atom is reset by the first run's set-up
    if (from)
    {
        bonds_->restoreBonds(from->bonds);
    }
    else
    {
        BondBuilder builder(ice);
        std::vector<BondPair> iceBonds;
        for (const BondPair& b : builder.build(rubble_.particles))
        {
            if (b.family == BondFamily::ice)
            {
                iceBonds.push_back(b);
            }
        }
        bonds_->createBonds(rubble_.particles, iceBonds);
        context_.log("Ice bonds inside the blocks: " + bondStatistics(iceBonds, int(rubble_.particles.size())).summary());
    }
    lmp_->command("run 0");
}


double RubbleScene::advance(long chunk, bool& first, double& t, const std::string& what)
{
    if (externalWater_)
    {
        externalWater_->advance(chunk);     // the settling's chunks are whole coupling intervals
    }
    else
    {
        // The first run after a set-up change makes its own set-up, as a resumed run's first does.
        lmp_->command("run " + std::to_string(chunk) + (first ? " post no" : " pre no post no"));
    }
    first = false;
    steps_ += chunk;
    t += chunk*dt_;
    const double ke = totalKineticEnergy(*lmp_)/double(blockOfTag_.size());
    if (!std::isfinite(ke) || !bonds_->failure().empty() || (waterForces_ && !waterForces_->failure().empty()))
    {
        const std::string why = !std::isfinite(ke) ? std::string("kinetic energy is not finite")
            : !bonds_->failure().empty() ? bonds_->failure() : waterForces_->failure();
        throw RunError(what + " blew up at t = " + formatNumber(t) + " s (step " + std::to_string(steps_) + "): " + why);
    }
    return ke;
}


void RubbleScene::writeSettlingCheckpoint(double t, double wallSeconds)
{
    // LIGGGHTS' restart first, named by its step, then the saved state that
    // names it, written atomically; older restarts go only after that, so a
    // run killed at any moment leaves a checkpoint whose restart is there.
    const std::string dir = context_.path("DEM");
    const std::string restartName = "settling.restart." + std::to_string(lmp_->step());
    lmp_->command("write_restart " + dir + "/settling.restart.tmp");
    SavedRubble state = gatherState(t);
    state.provenance = settlingInputs_.text();
    state.kind = SavedRubble::settlingCheckpoint;
    state.restart = restartName;
    state.wallSeconds = wallSeconds;
    if (context_.rank() == 0)
    {
        std::filesystem::rename(dir + "/settling.restart.tmp", dir + "/" + restartName);
        state.write(context_.path("DEM/settling.checkpoint.h5"));
        for (const auto& entry : std::filesystem::directory_iterator(dir))
        {
            const std::string name = entry.path().filename().string();
            if (name.rfind("settling.restart.", 0) == 0 && name != restartName)
            {
                std::filesystem::remove(entry.path());
            }
        }
    }
    MPI_Barrier(context_.comm());
    // What a resumed run does after reading the restart: a set-up (which
    // steps the bonds' histories once; the restore undoes it), the bonds
    // put back, another set-up.
    const std::vector<BondState> states = bonds_->bondStatesOfLocalAtoms();
    lmp_->command("run 0");
    bonds_->restoreBonds(states);
    lmp_->command("run 0");
}


Provenance RubbleScene::readSettlingInputs() const
{
    Provenance p;
    p.add("stage", "rubbleDEM settle");
    p.addDictionaryFile("constant/iceProperties", context_.path("constant/iceProperties"));
    // ends and compaction: the later stages'; blocks.shape as resolved with -shape below (the
    // dictionary's own is not what the blocks were made of when -shape overrode it)
    p.addDictionaryFile("constant/rubbleProperties", context_.path("constant/rubbleProperties"),
                        {"ends", "compaction", "blocks.shape"});
    p.add("block shape (with -shape)", name(settings_.shape));
    p.add("ice rained in: porosity of a blocks.rubbleThickness layer", exactNumber(settings_.expectedPorosity));
    const Dictionary coupling = Dictionary::readFile(context_.path("constant/couplingProperties"));
    p.addDictionary("constant/couplingProperties", coupling);
    if (std::filesystem::exists(context_.path("constant/g")))
    {
        p.addDictionaryFile("constant/g", context_.path("constant/g"));
    }
    p.addFileContent("DEM/in.rubbleBeam", context_.path("DEM/in.rubbleBeam"));
    if (water_.level == WaterLevel::cfd)
    {
        // The water that OpenFOAM solves while the blocks settle (iceRubbleFoam).
        for (const char* file : {"constant/transportProperties", "0/U", "0/p_rgh", "system/controlDict",
                                 "system/blockMeshDict", "system/fvSchemes", "system/fvSolution"})
        {
            p.addFileContent(file, context_.path(file));
        }
    }
    return p;
}


Provenance RubbleScene::readCompactionInputs() const
{
    Provenance p;
    p.add("stage", "rubbleDEM compact");
    p.addStage("DEM/settled.h5", settlingInputs_);
    const Dictionary rubble = Dictionary::readFile(context_.path("constant/rubbleProperties"));
    // releaseTime: the bonding stage's
    p.addDictionary("constant/rubbleProperties", rubble.subDict("compaction"), {"releaseTime"});
    return p;
}


Provenance RubbleScene::readBondingInputs() const
{
    Provenance p;
    p.add("stage", "rubbleDEM bond");
    if (settings_.compaction == CompactionMethod::plates)
    {
        p.addStage("DEM/compacted.h5", compactionInputs_);
    }
    else
    {
        p.addStage("DEM/settled.h5", settlingInputs_);
    }
    p.addDictionaryFile("constant/freezeBondProperties", context_.path("constant/freezeBondProperties"));
    const Dictionary rubble = Dictionary::readFile(context_.path("constant/rubbleProperties"));
    p.addDictionary("constant/rubbleProperties", rubble.subDict("ends"));
    p.add("compaction.releaseTime", exactNumber(settings_.releaseTime));
    return p;
}


SavedRubble RubbleScene::gatherState(double time) const
{
    const LAMMPS_NS::Atom& atom = *lmp_->engine().atom;
    std::vector<double> local;
    for (int i = 0; i < atom.nlocal; ++i)
    {
        local.push_back(atom.tag[i]);
        for (double** a : {atom.x, atom.v, atom.omega})
        {
            local.insert(local.end(), a[i], a[i] + 3);
        }
        local.push_back(atom.radius[i]);
        local.push_back(atom.rmass[i]/(4.0/3.0*M_PI*std::pow(atom.radius[i], 3)));
        local.push_back(atom.type[i]);
    }
    const std::vector<double> all = gatherDoubles(context_.comm(), local);
    SavedRubble s;
    s.bonds = gatherBondStates(context_.comm(), *bonds_);
    s.time = time;
    s.waterLevel = water_.hydrostatic.surfaceLevel;
    s.contactYoungsModulus = stageYoungsModulus_;
    s.description = "rubble of " + std::to_string(blockOfTag_.size()) + " particles, rubbleDEM";
    if (context_.rank() == 0)
    {
        s.particles.resize(blockOfTag_.size());
        for (std::size_t k = 0; k + 13 <= all.size(); k += 13)
        {
            SavedParticle& p = s.particles.at(static_cast<long>(all[k]) - 1);
            p.position = Vec3(all[k + 1], all[k + 2], all[k + 3]);
            p.velocity = Vec3(all[k + 4], all[k + 5], all[k + 6]);
            p.angularVelocity = Vec3(all[k + 7], all[k + 8], all[k + 9]);
            p.radius = all[k + 10];
            p.density = all[k + 11];
            p.type = static_cast<int>(all[k + 12]);
            p.block = blockOfTag_[static_cast<long>(all[k]) - 1];
        }
    }
    return s;
}


SettledLayer RubbleScene::measureLayer(double time, double kineticPerParticle, bool atRest) const
{
    return measureLayer(allPositionsByTag(*lmp_), time, kineticPerParticle, atRest);
}


SettledLayer RubbleScene::measureLayer
(
    const std::vector<Vec3>& positions, double time, double kineticPerParticle, bool atRest
) const
{
    const double r = 0.5*settings_.particleDiameter;
    std::vector<double> lows, highs;
    double volume = 0.0, above = 0.0;
    for (const Vec3& x : positions)
    {
        lows.push_back(x.z() - r);
        highs.push_back(x.z() + r);
        const double v = 4.0/3.0*M_PI*r*r*r;
        volume += v;
        if (water_.level != WaterLevel::none)
        {
            above += v - submergedSphereVolume(r, water_.hydrostatic.surfaceLevel - (x.z() - r));
        }
    }
    SettledLayer l;
    l.time = time;
    l.kineticEnergyPerParticle = kineticPerParticle;
    l.atRest = atRest;
    l.bottom = percentile(lows, 0.01);
    l.top = percentile(highs, 0.99);
    l.thickness = l.top - l.bottom;
    const double box = settings_.boxLength*settings_.boxWidth*l.thickness;
    l.porosity = 1.0 - rubble_.iceVolume/box;
    l.spherePorosity = 1.0 - volume/box;
    l.volumeAboveWater = above/volume;
    l.freeboard = l.top - water_.hydrostatic.surfaceLevel;
    return l;
}


void RubbleScene::settle()
{
    double t = 0.0;
    const std::string checkpoint = context_.path("DEM/settling.checkpoint.h5");
    if (settings_.resume && std::filesystem::exists(checkpoint))
    {
        const SavedRubble saved = SavedRubble::read(checkpoint, SavedRubble::settlingCheckpoint);
        requireSameInputs(Provenance::fromText(saved.provenance), settlingInputs_, checkpoint,
            "rubbleDEM -case " + settings_.caseDir + " -stage settle (without -resume)");
        const std::string restart = context_.path("DEM/" + saved.restart);
        if (saved.restart.empty() || !std::filesystem::exists(restart))
        {
            throw InputError(checkpoint, "restart", "names no LIGGGHTS restart that is there ('" + saved.restart
                + "'): start the settling again (without -resume)");
        }
        t = saved.time;
        settleWallBeforeResume_ = saved.wallSeconds;
        context_.log("Resuming the settling from " + checkpoint + " at t = " + formatNumber(t) + " s");
        startLiggghts(&saved, settlingIce_, restart);
        steps_ = lmp_->step();
        LAMMPS_NS::Update& update = *lmp_->engine().update;
        update.atime = update.ntimestep * dt_;
        update.atimestep = update.ntimestep;
    }
    else
    {
        startLiggghts(nullptr, settlingIce_);
    }
    const long n = static_cast<long>(blockOfTag_.size());
    std::ostringstream head;
    head << "Raining and settling: dt " << dt_ << " s, contacts and bonds at E = " << settings_.settlingYoungsModulus
         << " Pa, blocks unbreakable, hysteretic alpha " << settings_.settlingDampingAlpha << ", water "
         << toString(water_.level) << "; stops when the kinetic energy per particle < "
         << settings_.kineticEnergyThreshold << " J (after " << settings_.minTime << " s) or at " << settings_.maxTime << " s";
    context_.log(head.str());

    long chunk = std::max(1L, static_cast<long>(std::lround(settings_.checkInterval/dt_)));
    if (externalWater_)
    {
        const long k = externalWater_->stepsPerAdvance;
        chunk = (chunk + k - 1)/k*k;
        context_.log("No settling checkpoints at the " + externalWater_->name + " level (they would hold the "
            "DEM only): a killed settling starts again");
    }
    const auto start = std::chrono::steady_clock::now();
    const long startStep = steps_;
    const double startTime = t;
    double nextCheckpoint = t + settings_.checkpointInterval;
    double nextLog = t;
    int quietChecks = 0;
    double ke = 0.0;
    bool first = true;
    while (t < settings_.maxTime)
    {
        ke = advance(chunk, first, t, "settling");
        if (externalWater_)
        {
            // The resolved pressure on the ice jitters from step to step (coupling/README.md,
            // fluid-fraction jumps): the summary gives the water's force over the last second.
            waterForceSamples_.push_back(externalWater_->values());
            if (double(waterForceSamples_.size())*double(chunk)*dt_ > 1.0 + 1e-9)
            {
                waterForceSamples_.pop_front();
            }
        }
        quietChecks = (ke < settings_.kineticEnergyThreshold && t >= settings_.minTime) ? quietChecks + 1 : 0;
        const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        if (t >= nextLog || quietChecks >= 2)
        {
            std::ostringstream line;
            line << std::fixed << std::setprecision(2) << "  t = " << t << " s  kinetic energy "
                 << std::scientific << std::setprecision(2) << ke << " J/particle  "
                 << std::setprecision(2) << n*double(steps_ - startStep)/std::max(wall, 1e-9) << " particle-steps/s  "
                 << "at most " << formatDuration(wall/std::max(t - startTime, 1e-9)*(settings_.maxTime - t)) << " left";
            context_.log(line.str());
            nextLog = t + 1.0;
        }
        if (t >= nextCheckpoint && !externalWater_)
        {
            writeSettlingCheckpoint(t, settleWallBeforeResume_ + wall);
            first = true;       // the next run makes its set-up, as a resumed run's first does
            nextCheckpoint = t + settings_.checkpointInterval;
        }
        if (quietChecks >= 2)
        {
            break;
        }
    }
    settleWall_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    settleSteps_ = steps_ - startStep;
    layer_ = measureLayer(t, ke, quietChecks >= 2);
    std::ostringstream msg;
    msg << (layer_.atRest ? "Settled" : "NOT at rest") << " after " << t << " s (" << formatDuration(settleWall_)
        << "): layer " << layer_.bottom << " to " << layer_.top << " m, thickness " << layer_.thickness
        << " m, porosity " << layer_.porosity << " (spheres: " << layer_.spherePorosity << "), "
        << 100*layer_.volumeAboveWater << " % of the ice above water, freeboard " << layer_.freeboard << " m";
    context_.log(msg.str());
    SavedRubble state = gatherState(t);
    state.provenance = settlingInputs_.text();
    state.kind = SavedRubble::settledRubble;
    if (context_.rank() == 0)
    {
        state.write(context_.path("DEM/settled.h5"));
    }
    writeSettlingSummary();
}


void RubbleScene::writeSettlingSummary() const
{
    const LAMMPS_NS::Atom& atom = *lmp_->engine().atom;
    double mass = 0.0;
    for (int i = 0; i < atom.nlocal; ++i) mass += atom.rmass[i];
    const double weight = sumOverRanks(context_.comm(), mass)*water_.gravity.norm();
    if (context_.rank() != 0)
    {
        return;
    }
    const double particleSteps = double(blockOfTag_.size())*double(settleSteps_);   // of this run
    Json j;
    j["water"] = externalWater_ ? externalWater_->name : toString(water_.level);
    j["water_level_m"] = water_.hydrostatic.surfaceLevel;
    addSettledLayer(j, layer_);
    j["weight_N"] = weight;
    // The water's force on the ice (cfd: summed over the particles), mean and standard
    // deviation of the samples after each check interval over the last second.
    if (externalWater_ && !waterForceSamples_.empty())
    {
        const double n = double(waterForceSamples_.size());
        j["water_force_samples"] = long(waterForceSamples_.size());
        for (std::size_t k = 0; k < externalWater_->columns.size(); ++k)
        {
            double sum = 0.0, squares = 0.0;
            for (const std::vector<double>& sample : waterForceSamples_)
            {
                sum += sample.at(k);
                squares += sample.at(k)*sample.at(k);
            }
            const double mean = sum/n;
            j[externalWater_->columns[k] + "_N"] = mean;
            j[externalWater_->columns[k] + "_std_N"] = std::sqrt(std::max(0.0, squares/n - mean*mean));
        }
    }
    j["particles"] = long(blockOfTag_.size());
    j["steps"] = steps_;
    j["dt"] = dt_;
    j["ranks"] = long(context_.ranks());
    j["wall_s"] = settleWallBeforeResume_ + settleWall_;
    j["wall_before_resume_s"] = settleWallBeforeResume_;
    j["wall_per_simulated_s"] = settleWall_/std::max(double(settleSteps_)*dt_, 1e-12);   // of this run
    j["particle_steps_per_s"] = particleSteps/std::max(settleWall_, 1e-9);
    j["inputs_fingerprint"] = settlingInputs_.fingerprint();
    std::filesystem::create_directories(context_.path("postProcessing"));
    writeFileAtomically(context_.path("postProcessing/settling.json"), jsonText(j));
}


std::vector<ParticleSpec> RubbleScene::particlesNow() const
{
    const std::vector<Vec3> positions = allPositionsByTag(*lmp_);
    std::vector<ParticleSpec> particles(positions.size());
    for (std::size_t k = 0; k < particles.size(); ++k)
    {
        particles[k].position = positions[k];
        particles[k].radius = 0.5*settings_.particleDiameter;
        particles[k].block = blockOfTag_[k];
    }
    return particles;
}


OverlapStatistics RubbleScene::blockOverlaps() const
{
    const std::vector<ParticleSpec> particles = particlesNow();
    std::vector<Vec3> positions;
    for (const ParticleSpec& p : particles) positions.push_back(p.position);
    return overlapStatistics(particles, positions);
}


void RubbleScene::writeCompactionSummary() const
{
    if (context_.rank() != 0) return;
    const auto overlaps = [](const OverlapStatistics& o)
    {
        return Json{{"touching_block_pairs", o.touchingPairs}, {"mean_overlap_m", o.meanOverlap},
                    {"max_overlap_m", o.maxOverlap}};
    };
    Json j;
    j["youngs_modulus_Pa"] = compactionIce_.material.youngsModulus;
    j["target_porosity"] = settings_.targetPorosity;
    j["porosity_when_plates_touched"] = compacted_.startPorosity;
    j["porosity_when_closed"] = compacted_.closedPorosity > 0.0 ? Json(compacted_.closedPorosity) : Json();
    j["lid_pressure_when_closed_Pa"] = compacted_.closedLidPressure;
    j["overlaps_when_closed"] = overlaps(compacted_.closedOverlaps);
    j["hold_pressure_Pa"] = settings_.holdPressure;
    j["porosity_after_hold"] = compacted_.porosity;
    j["lid_pressure_after_hold_Pa"] = compacted_.lidPressure;
    j["floor_pressure_after_hold_Pa"] = compacted_.floorPressure;
    j["overlaps_after_hold"] = overlaps(compacted_.heldOverlaps);
    j["plate_bottom_m"] = compacted_.plateBottom;
    j["plate_top_m"] = compacted_.plateTop;
    j["compaction_and_hold_s"] = compacted_.time;
    j["steps"] = long(std::lround(compacted_.time/dt_));
    j["dt"] = dt_;
    j["wall_s"] = compacted_.wall;
    j["inputs_fingerprint"] = compactionInputs_.fingerprint();
    std::filesystem::create_directories(context_.path("postProcessing"));
    writeFileAtomically(context_.path("postProcessing/compaction.json"), jsonText(j));
}


void RubbleScene::compact()
{
    const auto start = std::chrono::steady_clock::now();
    const std::string file = context_.path("constant/rubbleProperties");
    const double area = settings_.boxLength*settings_.boxWidth;
    const double r = 0.5*settings_.particleDiameter;
    double low = HUGE_VAL, high = -HUGE_VAL;
    for (const Vec3& x : allPositionsByTag(*lmp_))
    {
        low = std::min(low, x.z() - r);
        high = std::max(high, x.z() + r);
    }
    const double bottom = std::max(0.0, low);    // not below the box floor
    const double finalGap = gapForPorosity(rubble_.iceVolume, area, settings_.targetPorosity);
    compacted_ = CompactedLayer();
    compacted_.startPorosity = porosityInGap(rubble_.iceVolume, area, high - bottom);
    if (finalGap < rubble_.blockThickness)
    {
        throw InputError(file, "compaction.targetPorosity", "porosity " + formatNumber(settings_.targetPorosity)
            + " needs the plates " + formatNumber(finalGap) + " m apart, less than one block ("
            + formatNumber(rubble_.blockThickness) + " m): the rubbled ice (" + formatNumber(rubble_.iceVolume)
            + " m3) cannot fill so thin a layer");
    }
    // The compacted layer is left where it floats: a uniform layer of ice
    // fraction (1 - p) floats with rho_i/rho_w of its height under the
    // surface (not below the box floor); in dry rubble it rests on the floor.
    double finalBottom = 0.0;
    if (water_.level != WaterLevel::none)
    {
        const double submerged = ice_.material.density/water_.hydrostatic.density;
        finalBottom = std::max(0.0, water_.hydrostatic.surfaceLevel - submerged*finalGap);
    }
    if (finalGap >= high - bottom)
    {
        context_.log("Compaction: the settled rubble is already at porosity " + formatNumber(compacted_.startPorosity)
            + " between its extremes, at or below the target " + formatNumber(settings_.targetPorosity)
            + ": the plates hold it where it is");
        plates_->place(bottom, high);
    }
    else
    {
        plates_->close(bottom, high, finalBottom, finalBottom + finalGap, settings_.compactionSpeed);
    }
    {
        std::ostringstream msg;
        msg << "Compacting: plates at z = " << bottom << " and " << high << " m (porosity "
            << compacted_.startPorosity << " between them) move at up to " << settings_.compactionSpeed
            << " m/s to z = " << finalBottom << " and " << finalBottom + finalGap << " m, " << finalGap
            << " m apart (porosity " << settings_.targetPorosity
            << "), then hold " << settings_.holdTime << " s, the lid backing off towards " << settings_.holdPressure
        << " Pa; stops if the lid pressure exceeds "
            << settings_.maxCompactionPressure << " Pa";
        context_.log(msg.str());
    }
    const long closingChunk = std::max(1L, static_cast<long>(std::lround(settings_.checkInterval/dt_)));
    // While it holds, the lid backs off every 10 ms towards holdPressure.
    const long holdingChunk = std::max(1L, static_cast<long>(std::lround(0.01/dt_)));
    const double targetTop = plates_->closed() ? high : finalBottom + finalGap;
    const double closingTime =
        std::max(std::abs(finalBottom - bottom), std::abs(finalBottom + finalGap - high))/settings_.compactionSpeed;
    double t = 0.0, holdUntil = HUGE_VAL, nextLog = 0.0;
    PlateLoads loads;
    // The blocks slide on each other with the compaction's friction while the
    // plates close, and hold with the settling's (SceneSetup's wall column: frictionless).
    const auto setFriction = [&](double mu)
    {
        lmp_->command("fix m5 all property/global coefficientFriction peratomtypepair 3 " + typePairMatrix(mu, 0.0));
    };
    setFriction(settings_.compactionFriction >= 0.0 ? settings_.compactionFriction
                                                    : settlingIce_.material.frictionCoefficient);
    bool first = true;
    // The compaction curve, written whole at the end or where the rubble jams.
    CsvWriter curve({"t", "gap", "porosity", "lid_Pa", "floor_Pa", "kinetic_energy_per_particle_J"});
    const std::string curvePath = context_.path("postProcessing/compaction.csv");
    const auto writeCurve = [&]()
    {
        if (context_.rank() != 0) return;
        std::filesystem::create_directories(context_.path("postProcessing"));
        curve.write(curvePath);
    };
    while (t < holdUntil)
    {
        const long chunk = holdUntil == HUGE_VAL ? closingChunk : holdingChunk;
        const double ke = advance(chunk, first, t, "compaction (t counted from its start)");
        loads = plates_->loads();
        const double porosity = porosityInGap(rubble_.iceVolume, area, plates_->gap());
        curve.addRow({t, plates_->gap(), porosity, loads.lid/area, loads.floor/area, ke});
        if (loads.lid/area > settings_.maxCompactionPressure)
        {
            writeCurve();
            const OverlapStatistics jammed = blockOverlaps();
            throw RunError("compaction stopped at porosity " + formatNumber(porosity) + " (plates "
                + formatNumber(plates_->gap()) + " m apart) with " + formatNumber(loads.lid/area) + " Pa on the lid, above "
                + file + " compaction.maxPressure " + formatNumber(settings_.maxCompactionPressure)
                + " Pa: the target porosity " + formatNumber(settings_.targetPorosity) + " is out of reach for these "
                "blocks (they jam; " + std::to_string(jammed.touchingPairs) + " touching block pairs overlap "
                + formatNumber(jammed.meanOverlap*1e6) + " um on average at contacts of E = "
                + formatNumber(compactionIce_.material.youngsModulus) + " Pa); aim higher, or allow more pressure "
                "(the curve: postProcessing/compaction.csv)");
        }
        if (plates_->closed() && holdUntil == HUGE_VAL)
        {
            holdUntil = t + settings_.holdTime;
            compacted_.closedPorosity = porosity;
            compacted_.closedLidPressure = loads.lid/area;
            compacted_.closedOverlaps = blockOverlaps();
            setFriction(settlingIce_.material.frictionCoefficient);
            first = true;   // the pair style reads the friction at the next set-up
        }
        else if (holdUntil != HUGE_VAL)
        {
            plates_->backOffLid(settings_.holdPressure*area, targetTop);   // never below the target gap
        }
        if (t >= nextLog)
        {
            const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            const double total = closingTime + settings_.holdTime;
            std::ostringstream line;
            line << std::fixed << std::setprecision(2) << "  t = " << t << " s  porosity " << std::setprecision(3)
                 << porosity << "  lid " << std::setprecision(0) << loads.lid/area << " Pa, floor " << loads.floor/area
                 << " Pa  kinetic energy " << std::scientific << std::setprecision(2) << ke << " J/particle  about "
                 << formatDuration(wall/std::max(t, 1e-9)*std::max(0.0, total - t)) << " left";
            context_.log(line.str());
            nextLog = t + 0.5;
        }
    }
    writeCurve();
    compacted_.plateBottom = plates_->bottom();
    compacted_.plateTop = plates_->top();
    compacted_.porosity = porosityInGap(rubble_.iceVolume, area, plates_->gap());
    compacted_.lidPressure = loads.lid/area;
    compacted_.floorPressure = loads.floor/area;
    compacted_.time = t;
    compacted_.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    compacted_.heldOverlaps = blockOverlaps();
    std::ostringstream msg;
    msg << "Compacted in " << t << " s (" << formatDuration(compacted_.wall) << "): porosity " << compacted_.startPorosity
        << " -> " << compacted_.closedPorosity << ", " << compacted_.porosity << " after a " << settings_.holdTime
        << " s hold, the lid backing off towards " << settings_.holdPressure << " Pa"
        << (compacted_.lidPressure > 1.5*settings_.holdPressure
            ? " (it did not reach it: each back-off moves the lid by the excess load over the stiffness of the"
              " spheres touching it, and the rubble behind them springs back by most of that)" : "")
        << "; plates at z = " << compacted_.plateBottom << " and "
        << compacted_.plateTop << " m; lid " << compacted_.lidPressure << " Pa, floor " << compacted_.floorPressure
        << " Pa at the end of the hold; contacts at E = " << compactionIce_.material.youngsModulus << " Pa: "
        << compacted_.closedOverlaps.touchingPairs << " touching block pairs, mean overlap "
        << compacted_.closedOverlaps.meanOverlap*1e6 << " um when closed (lid " << compacted_.closedLidPressure
        << " Pa), " << compacted_.heldOverlaps.touchingPairs << " pairs and " << compacted_.heldOverlaps.meanOverlap*1e6
        << " um after the hold";
    context_.log(msg.str());
    writeCompactionSummary();
    SavedRubble state = gatherState(t);
    state.provenance = compactionInputs_.text();
    state.kind = SavedRubble::compactedRubble;
    state.plateBottom = compacted_.plateBottom;
    state.plateTop = compacted_.plateTop;
    state.plateHoldPressure = settings_.holdPressure;
    if (context_.rank() == 0)
    {
        state.write(context_.path("DEM/compacted.h5"));
    }
}


void RubbleScene::release()
{
    const auto start = std::chrono::steady_clock::now();
    // The ends were fixed by type when the bonds were made: the integrated group follows.
    lmp_->command("unfix integrate");
    lmp_->command("group released type " + std::to_string(mobileType));
    lmp_->command("fix integrate released nve/sphere");
    plates_->withdraw();
    const long chunk = std::max(1L, static_cast<long>(std::lround(settings_.checkInterval/dt_)));
    const double minTime = std::min(0.2, settings_.releaseTime);
    double t = 0.0, ke = 0.0;
    int quietChecks = 0;
    bool first = true;
    while (t < settings_.releaseTime && quietChecks < 2)
    {
        ke = advance(chunk, first, t, "the release of the compacted rubble (t counted from the release)");
        quietChecks = (ke < settings_.kineticEnergyThreshold && t >= minTime) ? quietChecks + 1 : 0;
    }
    released_ = measureLayer(layer_.time + compacted_.time + t, ke, quietChecks >= 2);
    std::ostringstream msg;
    msg << "Released: plates withdrawn, " << (released_.atRest ? "at rest" : "NOT at rest") << " after " << t << " s ("
        << formatDuration(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count())
        << "): layer " << released_.bottom << " to " << released_.top << " m, thickness " << released_.thickness
        << " m, porosity " << released_.porosity << ", " << 100*released_.volumeAboveWater
        << " % of the ice above water (bonds at the compaction's stiffness, E = " << compactionIce_.material.youngsModulus
        << " Pa, unbreakable: the geometry the plates leave, not the bonds' strength)";
    context_.log(msg.str());
}


void RubbleScene::freezeBond()
{
    const std::vector<ParticleSpec> now = particlesNow();
    if
    (
        auto* heatBalance = dynamic_cast<HeatBalanceAreaCorrection*>(&freezeBondProperties_.areaCorrection())
    )
    {
        double volume = 0.0, surface = 0.0;
        for (const BuiltBlock& b : rubble_.blocks)
        {
            volume += b.volume;
            surface += b.surface;
        }
        const double bondRadius =
            ice_.family(BondFamily::freeze).radiusMultiplier*0.5*settings_.particleDiameter;
        heatBalance->setFromBlocks(volume, surface, bondRadius);
    }
    // The contact forces are those of the contact model the rubble came to rest with.
    freezeBonds_ = freezeBondsAtContacts(now, ice_, freezeBondProperties_, stageContact_.normalStiffness);
    freezeStats_ = freezeBondingStatistics(freezeBonds_, now);
    bonds_->addBonds(freezeBondStates(freezeBonds_, now, ice_));

    // The beam's two ends are fixed to the box.
    LAMMPS_NS::Atom& atom = *lmp_->engine().atom;
    const double end = settings_.fixedEndLength;
    long fixed = 0;
    for (int i = 0; i < atom.nlocal; ++i)
    {
        if (atom.x[i][0] - atom.radius[i] < end || atom.x[i][0] + atom.radius[i] > settings_.boxLength - end)
        {
            atom.type[i] = fixedType;
            ++fixed;
        }
    }
    fixed = sumOverRanks(context_.comm(), fixed);

    std::ostringstream msg;
    msg << "Freeze-bonds: " << freezeStats_.bonds << " between " << freezeStats_.blockContacts
        << " touching block pairs (" << freezeStats_.meanBondsPerBlockContact << " per block contact); confinement "
        << freezeStats_.meanConfinement*1e-3 << " kPa mean, " << freezeStats_.maxConfinement*1e-3
        << " kPa max; effective tensile " << freezeStats_.meanEffectiveTensile*1e-3 << " kPa, shear "
        << freezeStats_.meanEffectiveShear*1e-3 << " kPa; particle-level tensile " << freezeStats_.meanTensile*1e-3
        << " +- " << freezeStats_.sdTensile*1e-3 << " kPa, shear " << freezeStats_.meanShear*1e-3 << " +- "
        << freezeStats_.sdShear*1e-3 << " kPa on the bond area; " << freezeBondProperties_.summary() << "; "
        << fixed << " particles fixed at the ends";
    context_.log(msg.str());
}


void RubbleScene::writeSummary(double wallSeconds) const
{
    SavedRubble state = gatherState(layer_.time);
    state.provenance = bondingInputs_.text();
    state.kind = SavedRubble::bondedRubble;
    if (context_.rank() != 0)
    {
        return;
    }
    state.write(context_.path("DEM/rubble.h5"));
    std::filesystem::create_directories(context_.path("postProcessing"));
    std::filesystem::create_directories(context_.path("VTK"));

    CsvWriter strengths({"tagA", "tagB", "contact_force_N", "confinement_Pa", "tensile_Pa", "shear_Pa"});
    for (const NewFreezeBond& b : freezeBonds_)
    {
        strengths.addRow({double(b.pair.i + 1), double(b.pair.j + 1), b.contactForce, b.strength.confinement,
                          b.strength.tensile, b.strength.shear});
    }
    strengths.write(context_.path("postProcessing/freezeBonds.csv"));

    ParticleFrame particles;
    std::vector<int> bondCount(state.particles.size(), 0);
    BondFrame network;
    for (const BondState& b : state.bonds)
    {
        ++bondCount[b.tagA - 1];
        ++bondCount[b.tagB - 1];
        network.ends.push_back({b.tagA - 1, b.tagB - 1});
        network.family.push_back(static_cast<int>(b.family));
    }
    for (std::size_t k = 0; k < state.particles.size(); ++k)
    {
        const SavedParticle& p = state.particles[k];
        particles.position.push_back(p.position);
        particles.velocity.push_back(p.velocity);
        particles.radius.push_back(p.radius);
        particles.tag.push_back(long(k + 1));
        particles.bondCount.push_back(bondCount[k]);
        particles.fixed.push_back(p.type == fixedType);
        particles.block.push_back(p.block);
    }
    network.points = particles.position;
    writeParticlesVtp(context_.path("VTK/rubble_particles.vtp"), particles, settings_.vtkFormat);
    writeBondsVtp(context_.path("VTK/rubble_bonds.vtp"), network, settings_.vtkFormat);

    long iceBonds = 0;
    for (const BondState& b : state.bonds) iceBonds += b.family == BondFamily::ice;
    Json j;
    j["case"] = "rubbleBeam";
    j["block_shape"] = name(settings_.shape);
    j["blocks"] = long(rubble_.blocks.size());
    j["block_ice_volume_m3"] = rubble_.iceVolume;
    addSettledLayer(j, layer_);
    j["water_level_m"] = water_.hydrostatic.surfaceLevel;
    j["freeze_bonds"] = long(freezeStats_.bonds);
    j["block_contacts"] = long(freezeStats_.blockContacts);
    j["mean_bonds_per_block_contact"] = freezeStats_.meanBondsPerBlockContact;
    // Effective: c_f times the real strengths; the others are the particle-level
    // strengths the bonds break at (the same with particleStrengths direct).
    j["freeze_bond_particle_strengths"] = freezeBondProperties_.particleStrength().name();
    j["freeze_bond_effective_tensile_mean_Pa"] = freezeStats_.meanEffectiveTensile;
    j["freeze_bond_effective_shear_mean_Pa"] = freezeStats_.meanEffectiveShear;
    j["freeze_bond_tensile_mean_Pa"] = freezeStats_.meanTensile;
    j["freeze_bond_tensile_sd_Pa"] = freezeStats_.sdTensile;
    j["freeze_bond_shear_mean_Pa"] = freezeStats_.meanShear;
    j["freeze_bond_shear_sd_Pa"] = freezeStats_.sdShear;
    if (freezeBondProperties_.particleStrength().name() != "direct")
    {
        // What the virtual tests give with the mean particle strengths.
        const BondStrengthPair virtualTests =
            freezeBondProperties_.particleStrength().effective({freezeStats_.meanTensile, freezeStats_.meanShear});
        j["freeze_bond_virtual_test_tensile_Pa"] = virtualTests.tensile;
        j["freeze_bond_virtual_test_shear_Pa"] = virtualTests.shear;
    }
    j["confinement_mean_Pa"] = freezeStats_.meanConfinement;
    j["confinement_max_Pa"] = freezeStats_.maxConfinement;
    j["area_correction"] = freezeBondProperties_.areaCorrection().value();
    std::vector<double> confinements;
    for (const NewFreezeBond& b : freezeBonds_) confinements.push_back(b.strength.confinement);
    if (!confinements.empty())
    {
        j["confinement_percentiles_Pa"] = {{"p10", percentile(confinements, 0.10)},
            {"p50", percentile(confinements, 0.50)}, {"p90", percentile(confinements, 0.90)}};
    }
    double blockSurface = 0.0;
    for (const BuiltBlock& b : rubble_.blocks) blockSurface += b.surface;
    const double bondRadius = ice_.family(BondFamily::freeze).radiusMultiplier*0.5*settings_.particleDiameter;
    // each freeze-bond joins two blocks: its (DEM) area counts on both surfaces
    j["bonded_surface_fraction"] = 2.0*double(freezeStats_.bonds)*M_PI*bondRadius*bondRadius/blockSurface;
    if (settings_.compaction == CompactionMethod::plates)
    {
        j["compaction"] = {{"method", "plates"}, {"target_porosity", settings_.targetPorosity},
            {"youngs_modulus_Pa", compactionIce_.material.youngsModulus},
            {"porosity_when_plates_touched", compacted_.startPorosity > 0.0 ? Json(compacted_.startPorosity) : Json()},
            {"porosity_when_closed", compacted_.closedPorosity > 0.0 ? Json(compacted_.closedPorosity) : Json()},
            {"hold_pressure_Pa", settings_.holdPressure},
            {"porosity", compacted_.porosity},
            {"plate_bottom_m", compacted_.plateBottom}, {"plate_top_m", compacted_.plateTop},
            {"lid_pressure_at_bonding_Pa", compacted_.lidPressure},
            {"floor_pressure_at_bonding_Pa", compacted_.floorPressure},
            {"compaction_and_hold_s", compacted_.time}, {"wall_s", compacted_.wall}};
        j["released"] = {{"thickness_m", released_.thickness}, {"layer_bottom_m", released_.bottom},
            {"layer_top_m", released_.top}, {"porosity", released_.porosity},
            {"ice_volume_above_water_fraction", released_.volumeAboveWater}, {"freeboard_m", released_.freeboard},
            {"at_rest", released_.atRest}};
        j["compacted_inputs_fingerprint"] = compactionInputs_.fingerprint();
    }
    else
    {
        j["compaction"] = {{"method", "none"}};
    }
    j["ice_bonds"] = iceBonds;
    j["particles"] = long(state.particles.size());
    j["bonds"] = long(state.bonds.size());
    j["steps"] = steps_;
    j["dt"] = dt_;
    j["ranks"] = long(context_.ranks());
    j["settling_wall_s"] = settleWallBeforeResume_ + settleWall_;
    j["settled_inputs_fingerprint"] = settlingInputs_.fingerprint();
    j["inputs_fingerprint"] = bondingInputs_.fingerprint();
    j["wall_s"] = wallSeconds;
    writeFileAtomically(context_.path("postProcessing/summary.json"), jsonText(j));
}


SavedRubble RubbleScene::readStage(const std::string& file, const char* kind, const Provenance& inputs,
                                   const std::string& rebuildStage) const
{
    const std::string path = context_.path(file);
    if (!std::filesystem::exists(path))
    {
        throw InputError(path, "(file)", std::string("no ") + kind + ": run the " + rebuildStage + " stage first");
    }
    const SavedRubble saved = SavedRubble::read(path, kind);
    requireSameInputs(Provenance::fromText(saved.provenance), inputs, path,
        "rubbleDEM -case " + settings_.caseDir + " -stage " + rebuildStage);
    return saved;
}


void RubbleScene::startFromCompacted(const SavedRubble& compacted)
{
    startLiggghts(&compacted, compactionIce_, "", true);
    plates_->place(compacted.plateBottom, compacted.plateTop);
    lmp_->command("run 0");     // the plates' loads on the saved state
    const PlateLoads loads = plates_->loads();
    const double area = settings_.boxLength*settings_.boxWidth;
    compacted_.plateBottom = compacted.plateBottom;
    compacted_.plateTop = compacted.plateTop;
    compacted_.porosity = porosityInGap(rubble_.iceVolume, area, compacted.plateTop - compacted.plateBottom);
    compacted_.lidPressure = loads.lid/area;
    compacted_.floorPressure = loads.floor/area;
}


void RubbleScene::run()
{
    const auto start = std::chrono::steady_clock::now();
    context_.log(std::string(externalWater_ ? "iceRubbleFoam" : "rubbleDEM") + ": rubble beam, case " + settings_.caseDir + ", stage " + settings_.stage + ", "
        + std::to_string(context_.ranks()) + " rank(s)");
    const bool plates = settings_.compaction == CompactionMethod::plates;
    const bool bonding = settings_.stage == "bond" || settings_.stage == "all";
    settlingInputs_ = readSettlingInputs();
    if (plates)
    {
        compactionInputs_ = readCompactionInputs();
    }
    bondingInputs_ = readBondingInputs();
    buildBlocks();

    // Each stage starts from the saved state of the one before, in this run
    // or an earlier one alike, so that -stage all and the stages one by one
    // give the same rubble.
    SavedRubble settled;
    if (settings_.stage == "settle" || settings_.stage == "all")
    {
        settle();
        MPI_Barrier(context_.comm());   // rank 0 wrote it
        settled = SavedRubble::read(context_.path("DEM/settled.h5"), SavedRubble::settledRubble);
    }
    else
    {
        settled = readStage("DEM/settled.h5", SavedRubble::settledRubble, settlingInputs_, "settle");
        std::vector<Vec3> positions;
        for (const SavedParticle& p : settled.particles) positions.push_back(p.position);
        layer_ = measureLayer(positions, settled.time, 0.0, true);
    }
    if (plates && settings_.stage != "settle")
    {
        SavedRubble compacted;
        if (settings_.stage == "bond")
        {
            compacted = readStage("DEM/compacted.h5", SavedRubble::compactedRubble, compactionInputs_, "compact");
        }
        else
        {
            startLiggghts(&settled, compactionIce_, "", true);
            compact();
            MPI_Barrier(context_.comm());   // rank 0 wrote it
            compacted = SavedRubble::read(context_.path("DEM/compacted.h5"), SavedRubble::compactedRubble);
        }
        if (bonding)
        {
            const CompactedLayer measured = compacted_;
            startFromCompacted(compacted);
            if (settings_.stage == "all")
            {
                compacted_.startPorosity = measured.startPorosity;
                compacted_.closedPorosity = measured.closedPorosity;
                compacted_.closedLidPressure = measured.closedLidPressure;
                compacted_.closedOverlaps = measured.closedOverlaps;
                compacted_.heldOverlaps = measured.heldOverlaps;
                compacted_.time = measured.time;
                compacted_.wall = measured.wall;
            }
        }
    }
    else if (bonding && settings_.stage == "bond")
    {
        startLiggghts(&settled, settlingIce_);
        layer_.kineticEnergyPerParticle = totalKineticEnergy(*lmp_)/double(blockOfTag_.size());
    }
    if (bonding)
    {
        freezeBond();
        if (plates)
        {
            release();
        }
    }
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (bonding)
    {
        writeSummary(wall);
    }
    context_.log("Wall time " + formatDuration(wall));
}

} // namespace iceDEM
