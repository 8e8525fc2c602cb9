#include "RidgeScene.H"

#include "AtomicFile.H"
#include "BondBuilder.H"
#include "BondedBody.H"
#include "Dictionary.H"
#include "FreezeBonding.H"
#include "GivenAreaCorrection.H"
#include "IceBondForces.H"
#include "InputError.H"
#include "JsonObject.H"
#include "LiggghtsInstance.H"
#include "ParticleGather.H"
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

constexpr int mobileType = 1;
constexpr int fixedType = 2;
constexpr int boxTypes = 3;     // 3: the box walls
constexpr double platenOverhang = 0.05;     // m the platen reaches past each side wall

std::string number(double v)
{
    std::ostringstream s;
    s << std::setprecision(6) << v;
    return s.str();
}

} // namespace


std::string toString(RidgeTest t)
{
    return ridgeTestNames.nameOr(t, "?");
}


RidgeSettings RidgeSettings::read(int argc, char** argv)
{
    RidgeSettings s;
    const std::string usage = "allowed: -case DIR -stage assemble|load|all -resume";
    for (int k = 1; k < argc; ++k)
    {
        const std::string arg = argv[k];
        if (arg == "-case" && k + 1 < argc) s.caseDir = argv[++k];
        else if (arg == "-stage" && k + 1 < argc)
        {
            s.stage = argv[++k];
            if (s.stage != "assemble" && s.stage != "load" && s.stage != "all")
            {
                throw InputError("command line", "-stage", "'" + s.stage + "' is not one of: assemble load all");
            }
        }
        else if (arg == "-resume") s.resume = true;
        else throw InputError("command line", arg, "unknown option or missing value; " + usage);
    }
    // At the cfd level system/controlDict is OpenFOAM's (icePunchFoam).
    const bool cfd = WaterProperties::readCase(s.caseDir, true).level == WaterLevel::cfd;
    RidgeSettings fromCase = readCase(s.caseDir, cfd ? "system/loadingDict" : "system/controlDict");
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
    s.keelFile = keelFile.front() == '/' ? keelFile : s.caseDir + "/" + keelFile;
    s.trimDepth = keel.getScalarOrDefault("trimDepth", s.trimDepth);
    if (s.trimDepth < 0.0) keel.fail("trimDepth", "must not be negative");

    const Dictionary& cl = d.subDict("consolidatedLayer");
    cl.checkKeys({"thickness", "particleDiameter", "radiusSpread", "solidFraction", "seed"});
    s.layer.thickness = cl.getScalar("thickness");
    if (s.layer.thickness < 0.0) cl.fail("thickness", "must be 0 (a bare keel) or positive, in m");
    s.layer.particleDiameter = cl.getPositiveScalarOrDefault("particleDiameter", s.layer.particleDiameter);
    s.layer.radiusSpread = cl.getScalarOrDefault("radiusSpread", 0.0);
    if (s.layer.radiusSpread < 0.0 || s.layer.radiusSpread >= 0.9)
    {
        cl.fail("radiusSpread", "expected a relative half-width in [0, 0.9)");
    }
    s.layer.solidFraction = cl.getScalarOrDefault("solidFraction", 0.6);
    if (s.layer.solidFraction <= 0.0 || s.layer.solidFraction >= 0.74)
    {
        cl.fail("solidFraction", "expected a solid fraction in (0, 0.74)");
    }
    s.layer.seed = static_cast<unsigned>(cl.getLabelOrDefault("seed", 1));
    if (s.layer.thickness > 0.0 && s.layer.thickness < 1.25 * s.layer.particleDiameter)
    {
        cl.fail("thickness", "a layer thinner than 1.25 particle diameters cannot bend; "
                "use smaller particles or 0 for no layer");
    }

    const Dictionary& a = d.subDict("assembly");
    a.checkKeys({"pressDepth", "pressSpeed", "relaxTime", "youngsModulus", "dampingAlpha", "stiffenTime"});
    s.pressDepth = a.getScalarOrDefault("pressDepth", s.pressDepth);
    if (s.pressDepth < 0.0) a.fail("pressDepth", "must not be negative");
    s.pressSpeed = a.getPositiveScalarOrDefault("pressSpeed", s.pressSpeed);
    s.relaxTime = a.getScalarOrDefault("relaxTime", s.relaxTime);
    if (s.relaxTime < 0.0) a.fail("relaxTime", "must not be negative");
    s.assemblyYoungsModulus = a.getPositiveScalarOrDefault("youngsModulus", s.assemblyYoungsModulus);
    s.stiffenTime = a.getScalarOrDefault("stiffenTime", s.stiffenTime);
    if (s.stiffenTime < 0.0) a.fail("stiffenTime", "must not be negative (s; 0: bond at the soft contacts' overlaps)");
    s.assemblyDampingAlpha = a.getScalarOrDefault("dampingAlpha", s.assemblyDampingAlpha);
    if (s.assemblyDampingAlpha < 0.0 || s.assemblyDampingAlpha > 1.0)
    {
        a.fail("dampingAlpha", "expected a hysteretic alpha in [0, 1]");
    }

    const Dictionary& ends = d.subDict("ends");
    ends.checkKeys({"fixedLength"});
    s.fixedEndLength = ends.getScalar("fixedLength");
    if (s.fixedEndLength < 0.0 || 2.0 * s.fixedEndLength >= s.layer.length)
    {
        ends.fail("fixedLength", "expected 0 <= fixedLength < half the beam length");
    }

    const Dictionary& t = d.subDict("test");
    t.checkKeys({"type", "platenLength", "platenHeight", "settleTime", "speed", "initialGap"});
    s.test = ridgeTestNames.get(t, "type");
    s.platenLength = t.getPositiveScalarOrDefault("platenLength", s.platenLength);
    s.platenHeight = t.getPositiveScalarOrDefault("platenHeight", s.platenHeight);
    s.settleTime = t.getScalarOrDefault("settleTime", s.settleTime);
    if (s.settleTime < 0.0) t.fail("settleTime", "must not be negative");
    s.loading.speed = t.getPositiveScalarOrDefault("speed", s.loading.speed);
    s.loading.initialGap = t.getScalarOrDefault("initialGap", 0.002);
    if (s.loading.initialGap < 0.0) t.fail("initialGap", "must not be negative");
    if (s.test != RidgeTest::flexure && s.layer.thickness <= 0.0)
    {
        t.fail("type", toString(s.test) + " tests the bond between keel and consolidated layer: "
               "consolidatedLayer.thickness must be positive");
    }

    const Dictionary control = Dictionary::readFile(s.caseDir + "/" + controlFile);
    control.checkKeys
    ({
        "application", "maxTravel", "minTravel", "rampTravel", "blowUpFactor", "stopAfterHalfLoad", "travelAfterHalfLoad",
        "sampleInterval", "writeInterval", "checkpointInterval"
    });
    s.loading.readControl(control);
    return s;
}


RidgeScene::RidgeScene(MPI_Comm comm, const RidgeSettings& settings, const ExternalWater* externalWater)
:
    comm_(comm),
    settings_(settings),
    externalWater_(externalWater)
{
    MPI_Comm_rank(comm_, &rank_);
    MPI_Comm_size(comm_, &ranks_);
    ice_ = IceProperties::read(path("constant/iceProperties"));
    requireFreezeBondStrengthsPerBond(ice_, path("constant/iceProperties"));
    freezeBondProperties_ = FreezeBondProperties::read(path("constant/freezeBondProperties"));
    if (!dynamic_cast<const GivenAreaCorrection*>(&freezeBondProperties_.areaCorrection()))
    {
        throw InputError(path("constant/freezeBondProperties"), "areaCorrection.model",
            "a ridge needs `given` (c_f of its keel, see the keel's summary.json); the block shapes "
            "that heatBalance needs are not kept with the settled keel");
    }
    water_ = WaterProperties::readCase(settings_.caseDir, true);
    const bool loads = settings_.stage == "load" || settings_.stage == "all";
    if (externalWater_ && water_.level != WaterLevel::cfd)
    {
        throw InputError(path("constant/couplingProperties"), "waterLevel",
            "'" + toString(water_.level) + "': icePunchFoam solves the water of the loading stage; "
            "allowed here: cfd (hydrostatic: ridgeDEM)");
    }
    if (!externalWater_ && water_.level == WaterLevel::cfd && loads)
    {
        throw InputError(path("constant/couplingProperties"), "waterLevel",
            "cfd: ridgeDEM loads in still (hydrostatic) water and only assembles at the cfd level "
            "(-stage assemble); the loading stage at the cfd level runs in icePunchFoam "
            "(cases/rubblePunch: ./Allrun -water cfd)");
    }
    if (!externalWater_ && water_.level != WaterLevel::hydrostatic && water_.level != WaterLevel::cfd)
    {
        throw InputError(path("constant/couplingProperties"), "waterLevel",
            "ridgeDEM runs in still water: allowed here: hydrostatic (cfd: icePunchFoam, see coupling/README.md)");
    }
    if (water_.level == WaterLevel::cfd && !water_.hydrostatic.floatingSurface && settings_.stage != "load")
    {
        throw InputError(path("constant/couplingProperties"), "hydrostatic",
            "at the cfd level the ridge is still assembled in still water where it floats: needs "
            "hydrostatic { surfaceLevel floating; rho; mu; } (the fluid mesh ends at that level)");
    }
}


RidgeScene::~RidgeScene() = default;


std::string RidgeScene::path(const std::string& relative) const
{
    return settings_.caseDir + "/" + relative;
}


void RidgeScene::log(const std::string& line) const
{
    if (rank_ == 0)
    {
        std::cout << line << std::endl;
    }
}


void RidgeScene::run()
{
    log("ridgeDEM: " + toString(settings_.test) + " test of a ridge, case " + settings_.caseDir + ", "
        + std::to_string(ranks_) + " rank(s)");
    if (settings_.stage == "assemble" || settings_.stage == "all")
    {
        if (settings_.resume && std::filesystem::exists(path("DEM/ridge.h5")))
        {
            log("Resuming: the ridge is already assembled (DEM/ridge.h5)");
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


void RidgeScene::chooseContactsAndStep(const std::vector<ParticleSpec>& particles, const IceProperties& ice)
{
    double minRadius = HUGE_VAL, meanDiameter = 0.0;
    for (const ParticleSpec& p : particles)
    {
        minRadius = std::min(minRadius, p.radius);
        meanDiameter += 2.0 * p.radius / particles.size();
    }
    const double minMass = ice.material.density * 4.0 / 3.0 * M_PI * std::pow(minRadius, 3);
    contact_ = ContactParameters::of(ice, meanDiameter, minMass);
    const TimeStepLimits limits = timeStepLimits(ice, minRadius, ice.maxBondsPerParticle);
    dt_ = chooseTimeStep(ice, limits, path("constant/iceProperties"));
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
    const OverlapStatistics before = overlapStatistics(particles, allPositionsByTag(*lmp_));
    const double soft = settings_.assemblyYoungsModulus;
    const double hard = ice_.material.youngsModulus;
    long steps = 0;
    for (int k = 1; k <= stages; ++k)
    {
        const double modulus = soft * std::pow(hard / soft, static_cast<double>(k) / stages);
        const IceProperties stage = ice_.softenedForAssembly(modulus, settings_.assemblyDampingAlpha);
        chooseContactsAndStep(particles, stage);
        setContactStiffness();
        bonds_->changeProperties(stage);
        const long n = std::max(1L, std::lround(settings_.stiffenTime / stages / dt_));
        lmp_->command("run " + std::to_string(n));
        steps += n;
    }
    const OverlapStatistics after = overlapStatistics(particles, allPositionsByTag(*lmp_));
    std::ostringstream msg;
    msg << "Contacts stiffened from E = " << soft << " to " << hard << " Pa over " << settings_.stiffenTime
        << " s (" << stages << " stages, " << steps << " steps): touching pairs between blocks " << before.touchingPairs
        << " -> " << after.touchingPairs << ", mean overlap " << before.meanOverlap * 1e6 << " -> "
        << after.meanOverlap * 1e6 << " um, largest " << before.maxOverlap * 1e6 << " -> "
        << after.maxOverlap * 1e6 << " um";
    log(msg.str());
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
    const std::string& readParticles
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
    if (rank_ == 0)
    {
        std::filesystem::create_directories(path("DEM"));
        std::filesystem::create_directories(path("postProcessing"));
        writeLiggghtsData
        (
            path("DEM/ridge.data"), "ridge written by ridgeDEM", particles, ice.material.density, boxLow_, boxHigh_,
            boxTypes, [&](const ParticleSpec& p) { return types[&p - particles.data()]; }
        );
    }
    MPI_Barrier(comm_);

    LiggghtsInstance::reportErrorsFromLog(path("log.liggghts"));
    lmp_ = std::make_unique<LiggghtsInstance>(comm_, path("log.liggghts"));
    const double skin = 0.2 * maxRadius;
    ScriptVariables variables
    {
        {"readParticles", "\"" + readParticles + "\""},
        {"ghostCutoff", exactNumber(bondGhostCutoff(ice, maxRadius, skin))},
        {"neighbourSkin", exactNumber(skin)},
        {"dt", exactNumber(dt_)},
        {"gravity", exactNumber(water_.gravity.norm())},
        {"boxWidth", exactNumber(settings_.layer.width)},
        {"layerFirstTag", std::to_string(layerFirstTag_)}
    };
    const ScriptVariables contacts = boxContactVariables(contact_);
    variables.insert(variables.end(), contacts.begin(), contacts.end());
    defineScriptVariables(*lmp_, variables, path("DEM/variables.generated"), "ridgeDEM");
    const std::string script = path("DEM/in.ridge");
    if (!std::filesystem::exists(script))
    {
        throw InputError(script, "(file)", "the LIGGGHTS input script is missing");
    }
    lmp_->runScript(script);
}


void RidgeScene::assemble()
{
    const auto wallStart = std::chrono::steady_clock::now();
    if (!std::filesystem::exists(settings_.keelFile))
    {
        throw InputError(path("constant/ridgeProperties"), "keel.settledRubble",
            "'" + settings_.keelFile + "' does not exist: build the keel first (its rubble case's "
            "./Allrun, or rubbleDEM -stage settle)");
    }
    const SavedRubble keel = SavedRubble::read(settings_.keelFile);
    const RidgeLayout layout = assembleRidge(keel.particles, settings_.layer, settings_.trimDepth);
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
        log(msg.str());
    }

    // Pressing: the keel with soft contacts and unbreakable blocks (as it
    // settled), the layer rigid (fixed type, moved by LIGGGHTS).
    const IceProperties soft = ice_.softenedForAssembly(settings_.assemblyYoungsModulus, settings_.assemblyDampingAlpha);
    std::vector<int> types(layout.particles.size(), mobileType);
    for (std::size_t k = layout.keelParticles; k < types.size(); ++k) types[k] = fixedType;
    chooseContactsAndStep(layout.particles, soft);
    startLiggghts(layout.particles, types, soft, "read_data " + path("DEM/ridge.data"));

    waterForces_ = std::make_unique<WaterForces>(*lmp_, HydrostaticWater(waterParameters));
    waterForces_->defineForceFix();
    bonds_ = std::make_unique<IceBondForces>(*lmp_, soft);
    lmp_->command("fix iceBondForces all external pf/callback 1 1");
    bonds_->attach("iceBondForces");
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

    const long pressSteps = layerCount > 0
        ? std::lround(settings_.pressDepth / (settings_.pressSpeed * dt_)) : 0;
    const long relaxSteps = layerCount > 0 ? std::lround(settings_.relaxTime / dt_) : 0;
    if (pressSteps > 0)
    {
        log("Pressing the layer " + number(settings_.pressDepth * 1e3) + " mm into the keel at "
            + number(settings_.pressSpeed) + " m/s (" + std::to_string(pressSteps) + " steps of " + number(dt_) + " s)");
        lmp_->command("fix pressLayer layer move linear 0 0 " + exactNumber(-settings_.pressSpeed));
        lmp_->command("run " + std::to_string(pressSteps));
        lmp_->command("unfix pressLayer");
    }
    if (relaxSteps > 0)
    {
        log("Keel settling under the held layer for " + number(settings_.relaxTime) + " s ("
            + std::to_string(relaxSteps) + " steps)");
        lmp_->command("velocity layer set 0 0 0");
        lmp_->command("run " + std::to_string(relaxSteps));
    }

    if (settings_.stiffenTime > 0.0)
    {
        stiffenContacts(layout.particles);
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
    ridge.description = "ridge assembled by ridgeDEM from " + settings_.keelFile + ": keel trimmed by "
        + number(settings_.trimDepth) + " m, consolidated layer " + number(settings_.layer.thickness)
        + " m (block " + std::to_string(layout.clBlock) + "), pressed " + number(settings_.pressDepth) + " m";

    RidgeGeometry geometry = measureRidge(ridge.particles, layout.clBlock, settings_.layer.length, settings_.layer.width);
    geometry.waterLevel = ridge.waterLevel;
    if (rank_ == 0)
    {
        ridge.write(path("DEM/ridge.h5"));
        writeGeometry(geometry, ridge.particles);
    }
    // The load stage reads ridge.h5 on every rank next (-stage all).
    MPI_Barrier(comm_);
    std::ostringstream msg;
    msg << "Bonds: " << iceBonds.size() << " ice bonds (blocks and layer), " << freezeStats.bonds
        << " freeze-bonds (" << layerToKeel << " between layer and keel); tensile "
        << freezeStats.meanTensile * 1e-3 << " kPa, shear " << freezeStats.meanShear * 1e-3
        << " kPa on the bond area (" << freezeBondProperties_.summary() << "); " << fixedEnds
        << " particles fixed at the ends; depth " << geometry.depth() << " m; assembled in "
        << formatDuration(std::chrono::duration<double>(std::chrono::steady_clock::now() - wallStart).count())
        << "; saved DEM/ridge.h5";
    log(msg.str());

    bonds_.reset();
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
    std::ostringstream j;
    j << std::setprecision(10) << "{\"length\": " << g.length << ", \"width\": " << g.width
      << ", \"x0\": 0, \"y0\": 0,\n \"layers\": [{\"name\": \"keel\", \"zBottom\": " << g.keelBottom
      << ", \"zTop\": " << g.keelTop << "}";
    if (g.hasLayer())
    {
        j << ",\n            {\"name\": \"consolidatedLayer\", \"zBottom\": " << g.clBottom
          << ", \"zTop\": " << g.clTop << "}";
    }
    j << "],\n \"loadX\": " << 0.5 * g.length << ", \"loadHalfLength\": " << 0.5 * settings_.platenLength
      << ", \"supports\": [" << settings_.fixedEndLength << ", " << g.length - settings_.fixedEndLength
      << "], \"waterLevel\": " << g.waterLevel << ",\n \"particleRadius\": " << g.particleRadius
      << ", \"depth\": " << g.depth() << ", \"test\": \"" << toString(settings_.test) << "\",\n"
      << " \"overlapsBetweenBlocksAtBonding\": {\"touchingPairs\": " << atBonding.touchingPairs
      << ", \"mean\": " << atBonding.meanOverlap << ", \"max\": " << atBonding.maxOverlap << "}}\n";
    writeFileAtomically(path("postProcessing/geometry.json"), j.str());
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
    if (settings_.test == RidgeTest::flexure)
    {
        // Force of the ice on the platen, which they push up.
        return lmp_->fix("platen").compute_vector(2);
    }
    // What the actuator holding the layer must apply: minus the net force of
    // bonds, contacts, gravity and water on the layer's particles.
    const int axis = settings_.test == RidgeTest::pullUp ? 2 : 0;
    const LAMMPS_NS::Atom& atom = *lmp_->engine().atom;
    double local = 0.0;
    for (int i = 0; i < atom.nlocal; ++i)
    {
        if (atom.tag[i] >= layerFirstTag_) local -= atom.f[i][axis];
    }
    return sumOverRanks(comm_, local);
}


std::vector<double> RidgeScene::waterColumns()
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
        submerged = sumOverRanks(comm_, local);
        buoyancy = water.buoyancy(submerged);
    }
    if (submergedAtStart_ < 0.0)
    {
        submergedAtStart_ = submerged;
    }
    const double share = water.buoyancy(submerged - submergedAtStart_);
    double platenBuoyancy = 0.0;
    if (settings_.test == RidgeTest::flexure)
    {
        const double bottom = platenBottom_ - settings_.loading.travelAt(lmp_->time() - loading_->state().startTime);
        platenBuoyancy = water.buoyancy(water.submergedPrismVolume(
            settings_.platenLength * (settings_.layer.width + 2.0 * platenOverhang), bottom, bottom + settings_.platenHeight));
    }
    std::vector<double> columns{buoyancy, submerged, share, platenBuoyancy};
    if (externalWater_)
    {
        const std::vector<double> own = externalWater_->values();
        columns.insert(columns.end(), own.begin(), own.end());
    }
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


void RidgeScene::load()
{
    const auto wallStart = std::chrono::steady_clock::now();
    if (!std::filesystem::exists(path("DEM/ridge.h5")))
    {
        throw InputError(path("DEM/ridge.h5"), "(file)", "missing: run the assemble stage first (-stage assemble)");
    }
    const SavedRubble ridge = SavedRubble::read(path("DEM/ridge.h5"));
    int maxBlock = -1;
    for (const SavedParticle& p : ridge.particles) maxBlock = std::max(maxBlock, p.block);
    const int layerBlock = settings_.layer.thickness > 0.0 ? maxBlock : -1;
    RidgeGeometry geometry = measureRidge(ridge.particles, layerBlock, settings_.layer.length, settings_.layer.width);
    geometry.waterLevel = ridge.waterLevel;
    if (rank_ == 0)
    {
        writeGeometry(geometry, ridge.particles);
    }
    layerFirstTag_ = geometry.keelParticles + 1;

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
        // Keel-bond tests hold the keel and move the layer (fix move): neither is
        // integrated. The layer keeps type 1 (LIGGGHTS' granular models need it).
        types[k] = settings_.test == RidgeTest::flexure ? s.type
            : static_cast<long>(k) >= geometry.keelParticles ? mobileType : fixedType;
        if (std::abs(s.position.x() - xLoad) < 0.5 * settings_.platenLength + s.radius)
        {
            topUnderPlaten = std::max(topUnderPlaten, s.position.z() + s.radius);
        }
    }
    chooseContactsAndStep(particles, ice_);
    std::vector<std::string> waterColumnNames{"buoyancy", "submergedVolume", "buoyancyShare", "platenBuoyancy"};
    if (externalWater_)
    {
        if (settings_.resume)
        {
            throw InputError("command line", "-resume", "a checkpoint holds the DEM only, not the "
                + externalWater_->name + " water: a run at that level starts again");
        }
        waterColumnNames.insert(waterColumnNames.end(), externalWater_->columns.begin(), externalWater_->columns.end());
    }
    loading_ = std::make_unique<PlatenLoading>
    (
        comm_, settings_.caseDir, externalWater_ ? "icePunchFoam" : "ridgeDEM", settings_.loading, dt_,
        particleCount_, fixedType, waterColumnNames
    );
    std::unique_ptr<Checkpoint> checkpoint;
    if (settings_.resume && loading_->checkpointExists())
    {
        checkpoint = std::make_unique<Checkpoint>(loading_->readCheckpoint());
    }
    startLiggghts
    (
        particles, types, ice_,
        checkpoint ? "read_restart " + loading_->restartFile(*checkpoint) : "read_data " + path("DEM/ridge.data")
    );
    if (settings_.test != RidgeTest::flexure)
    {
        lmp_->command("unfix integrate");
    }

    // The test's own fixes come before the water and the bonds (the bonds'
    // hysteretic damping acts on the total force).
    platenBottom_ = topUnderPlaten + settings_.loading.initialGap;
    if (settings_.test == RidgeTest::flexure)
    {
        if (rank_ == 0)
        {
            writeBoxStl
            (
                path("DEM/platen.stl"),
                Vec3(xLoad - 0.5 * settings_.platenLength, -platenOverhang, platenBottom_),
                Vec3(xLoad + 0.5 * settings_.platenLength, settings_.layer.width + platenOverhang,
                     platenBottom_ + settings_.platenHeight),
                "platen"
            );
        }
        MPI_Barrier(comm_);
        lmp_->command("fix platen all mesh/surface/stress file " + path("DEM/platen.stl") + " type 1");
        lmp_->command("fix platenWall all wall/gran model hooke/stiffness tangential history rolling_friction epsd2 "
                      "mesh n_meshes 1 meshes platen absolute_damping on");
    }
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
    bonds_ = std::make_unique<IceBondForces>(*lmp_, ice_);
    lmp_->command("fix iceBondForces all external pf/callback 1 1");
    bonds_->attach("iceBondForces");
    if (settings_.test == RidgeTest::flexure && waterForces_)
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

    const long settleSteps = settings_.test == RidgeTest::flexure ? std::lround(settings_.settleTime / dt_) : 0;
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
        log("Settled under gravity and buoyancy for " + number(settings_.settleTime) + " s: kinetic energy "
            + number(totalKineticEnergy(*lmp_)) + " J");
    }
    // The test moves off smoothly (loading.rampTravel): a sudden start would
    // hit the ice with a force spike.
    const long startStep = checkpoint ? checkpoint->state.liggghtsStepAtStart : lmp_->step();
    const std::string speed = settings_.loading.speedFormula(startStep, dt_);
    const std::string travel = settings_.loading.travelFormula(startStep, dt_);
    lmp_->command("variable zero equal 0");
    if (settings_.test == RidgeTest::flexure)
    {
        lmp_->command("variable platenVz equal -" + speed);
        lmp_->command("fix movePlaten all move/mesh mesh platen linear/variable v_zero v_zero v_platenVz");
    }
    else
    {
        lmp_->command("variable layerV equal " + speed);
        lmp_->command("variable layerD equal " + travel);
        // Every component given: a NULL one would be integrated from the forces.
        lmp_->command(settings_.test == RidgeTest::pullUp
            ? "fix moveLayer layer move variable v_zero v_zero v_layerD v_zero v_zero v_layerV"
            : "fix moveLayer layer move variable v_layerD v_zero v_zero v_layerV v_zero v_zero");
    }
    // The loading runs skip LIGGGHTS' set-up (pre no); a moving mesh is only
    // registered as moving by one, so the motion gets its own.
    lmp_->command("run 0 post no");

    std::ostringstream msg;
    msg << "Loading: " << particleCount_ << " particles (" << geometry.keelParticles << " keel, "
        << geometry.layerParticles << " layer), " << ridge.bonds.size() << " bonds, depth "
        << geometry.depth() << " m, water surface " << ridge.waterLevel << " m, time step " << dt_ << " s";
    log(msg.str());

    PlatenLoading::Hooks hooks;
    hooks.force = [this] { return testForce(); };
    hooks.extras = [this] { return waterColumns(); };
    hooks.stopEjecta = [this] { return stopParticlesAtBoxEdge(); };
    if (externalWater_)
    {
        hooks.advance = externalWater_->advance;
        hooks.stepsPerAdvance = externalWater_->stepsPerAdvance;
    }
    loading_->run(*lmp_, *bonds_, hooks);

    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wallStart).count();
    writeSummary(geometry, wall);
    log("End: " + std::to_string(loading_->state().steps) + " steps in " + formatDuration(wall) + ", "
        + std::to_string(loading_->breakage().size()) + " bonds broken");
}


void RidgeScene::writeSummary(const RidgeGeometry& g, double wallSeconds) const
{
    if (rank_ != 0)
    {
        return;
    }
    const CsvWriter& curve = loading_->curve();
    const BreakageRecord& breaks = loading_->breakage();
    const std::size_t rows = curve.nRows();
    double peak = -HUGE_VAL, travelAtPeak = 0.0, shareAtPeak = 0.0;
    const double startForce = rows > 0 ? curve.row(0)[PlatenLoading::forceColumn] : 0.0;
    const std::vector<std::string>& columns = curve.columns();
    const std::size_t shareColumn =
        std::find(columns.begin(), columns.end(), "buoyancyShare") - columns.begin();
    for (std::size_t k = 0; k < rows; ++k)
    {
        const std::vector<double>& row = curve.row(k);
        if (row[PlatenLoading::forceColumn] > peak)
        {
            peak = row[PlatenLoading::forceColumn];
            travelAtPeak = row[PlatenLoading::travelColumn];
            shareAtPeak = row[shareColumn];
        }
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

    const double L = g.length, B = g.width, D = g.depth(), sigmaF1 = 902e3;
    JsonObject byMode;
    byMode.add("tension", long(breaks.count(BreakMode::tension))).add("shear", long(breaks.count(BreakMode::shear)))
          .add("twist", long(breaks.count(BreakMode::twist))).add("bending", long(breaks.count(BreakMode::bending)));
    JsonObject byFamily;
    byFamily.add("ice", long(breaks.count(BondFamily::ice))).add("freeze", long(freezeBroken));

    JsonObject j;
    j.add("case", "ridge").add("test", toString(settings_.test))
     .add("water", externalWater_ ? externalWater_->name : toString(water_.level))
     .add("consolidated_layer_m", settings_.layer.thickness)
     .add("keel_thickness_m", g.keelTop - g.keelBottom)
     .add("depth_m", D)
     .add("water_level_m", g.waterLevel)
     .add("freeze_bond_set", freezeBondProperties_.summary())
     .add("peak_force_N", peak)
     .add("travel_at_peak_m", travelAtPeak)
     .add("force_at_start_N", startForce)
     .add("buoyancy_share_at_peak_N", shareAtPeak)
     .add("peak_force_without_buoyancy_N", peak - shareAtPeak);
    if (settings_.test == RidgeTest::flexure)
    {
        j.add("flexural_strength_Pa", 3.0 * peak * L / (2.0 * B * D * D))
         .add("equivalent_thickness_m", std::sqrt(3.0 * peak * L / (2.0 * sigmaF1 * B)))
         .add("sigma_f1_Pa", sigmaF1);
    }
    else
    {
        j.add("interface_area_m2", L * B)
         .add("interface_strength_Pa", (peak - startForce) / (L * B));
    }
    j.add("broken_bonds", long(breaks.size()))
     .add("broken_by_mode", byMode)
     .add("broken_by_family", byFamily)
     .add("freeze_bonds_broken_in_tension_share", freezeBroken > 0 ? double(freezeTension) / freezeBroken : 0.0)
     .add("layer_keel_bonds_broken", long(interfaceBroken))
     .add("particles", particleCount_)
     .add("keel_particles", g.keelParticles)
     .add("layer_particles", g.layerParticles)
     .add("platen_speed_m_per_s", settings_.loading.speed)
     .add("ejected_particles_stopped", long(loading_->state().frozenEjecta))
     .add("steps", loading_->state().steps)
     .add("dt", dt_)
     .add("ranks", ranks_)
     .add("wall_s", wallSeconds)
     .add("loop_wall_s", loading_->loopSeconds())
     .add("particle_steps_per_s", loading_->loopSeconds() > 0.0
          ? loading_->loopSteps() * double(particleCount_) / loading_->loopSeconds() : 0.0);
    writeFileAtomically(path("postProcessing/summary.json"), j.text() + "\n");
}

} // namespace iceDEM
