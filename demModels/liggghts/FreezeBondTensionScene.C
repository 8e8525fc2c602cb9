#include "FreezeBondTensionScene.H"

#include "AtomicFile.H"
#include "BondBuilder.H"
#include "BondModel.H"
#include "Dictionary.H"
#include "IceBlocks.H"
#include "IceBondForces.H"
#include "InputError.H"
#include "JsonObject.H"
#include "LiggghtsInstance.H"
#include "ParticleGather.H"
#include "SceneSetup.H"
#include "TimeStep.H"

#include "atom.h"
#include "group.h"
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

constexpr int bodyType = 1;
constexpr int lowerGripType = 2;
constexpr int upperGripType = 3;

double positiveEntry(const Dictionary& d, const std::string& key, double def)
{
    const double v = d.getScalarOrDefault(key, def);
    if (!(v > 0.0))
    {
        d.fail(key, "must be positive");
    }
    return v;
}

} // namespace


TensionTestSettings TensionTestSettings::read(int argc, char** argv)
{
    TensionTestSettings s;
    double pressure = -1.0, time = -1.0;
    for (int k = 1; k < argc; ++k)
    {
        const std::string arg = argv[k];
        auto value = [&]()
        {
            if (k + 1 >= argc)
            {
                throw InputError("command line", arg, "needs a value");
            }
            return std::string(argv[++k]);
        };
        auto number = [&]()
        {
            const std::string v = value();
            try
            {
                std::size_t used = 0;
                const double x = std::stod(v, &used);
                if (used == v.size() && x > 0.0) return x;
            }
            catch (const std::exception&) {}
            throw InputError("command line", arg, "needs a positive number, got '" + v + "'");
        };
        if (arg == "-case") s.caseDir = value();
        else if (arg == "-label") s.label = value();
        else if (arg == "-pressure") pressure = number();
        else if (arg == "-time") time = number();
        else
        {
            throw InputError("command line", arg,
                "unknown option; allowed: -case DIR -label NAME -pressure PA -time MIN");
        }
    }
    const Dictionary d = Dictionary::readFile(s.caseDir + "/constant/tensionTestProperties");
    d.checkKeys({"specimen", "loading"});
    const Dictionary& sp = d.subDict("specimen");
    sp.checkKeys({"diameter", "halfLength", "particleDiameter", "polygonSides"});
    s.diameter = positiveEntry(sp, "diameter", s.diameter);
    s.halfLength = positiveEntry(sp, "halfLength", s.halfLength);
    s.particleDiameter = positiveEntry(sp, "particleDiameter", s.particleDiameter);
    s.polygonSides = sp.getLabelOrDefault("polygonSides", s.polygonSides);
    if (s.polygonSides < 6) sp.fail("polygonSides", "must be at least 6");
    if (s.particleDiameter*4 > s.diameter) sp.fail("particleDiameter", "must be at most a quarter of the diameter");
    if (s.particleDiameter*3 > s.halfLength) sp.fail("particleDiameter", "must be at most a third of halfLength");
    const Dictionary& l = d.subDict("loading");
    l.checkKeys({"confinementPressure", "confinementTime", "pullSpeed", "maxPull", "samples"});
    s.confinementPressure = positiveEntry(l, "confinementPressure", s.confinementPressure);
    s.confinementTime = positiveEntry(l, "confinementTime", s.confinementTime);
    s.pullSpeed = positiveEntry(l, "pullSpeed", s.pullSpeed);
    s.maxPull = positiveEntry(l, "maxPull", s.maxPull);
    s.samples = l.getLabelOrDefault("samples", s.samples);
    if (s.samples < 10) l.fail("samples", "must be at least 10");
    if (pressure > 0.0) s.confinementPressure = pressure;
    s.submersionTime = time;     // < 0: the one in constant/freezeBondProperties
    if (s.label.empty())
    {
        std::ostringstream label;
        label << "p" << s.confinementPressure*1e-3 << "kPa";
        if (time > 0.0) label << "_t" << time << "min";
        s.label = label.str();
    }
    return s;
}


FreezeBondTensionScene::FreezeBondTensionScene(MPI_Comm comm, const TensionTestSettings& settings)
:
    comm_(comm),
    settings_(settings),
    curve_({"time_s", "pull_m", "force_N", "stress_Pa", "intact_freeze_bonds"})
{
    MPI_Comm_rank(comm_, &rank_);
    MPI_Comm_size(comm_, &ranks_);
    ice_ = IceProperties::read(path("constant/iceProperties"));
    if (ice_.family(BondFamily::freeze).strengthModel != StrengthModel::perBond)
    {
        throw InputError(path("constant/iceProperties"), "bondFamilies.freeze.strengthModel",
            "must be freezeBondProperties: freeze-bond strengths come from constant/freezeBondProperties");
    }
    strengthModel_ = FreezeBondStrengthModel::read(path("constant/freezeBondProperties"));
    if (settings_.submersionTime > 0.0)
    {
        strengthModel_.setSubmersionTime(settings_.submersionTime);
    }
    settings_.submersionTime = strengthModel_.submersionTime();
}


FreezeBondTensionScene::~FreezeBondTensionScene() = default;


std::string FreezeBondTensionScene::path(const std::string& relative) const
{
    return settings_.caseDir + "/" + relative;
}


void FreezeBondTensionScene::log(const std::string& line) const
{
    if (rank_ == 0)
    {
        std::cout << line << std::endl;
    }
}


void FreezeBondTensionScene::buildSpecimen()
{
    const double d = settings_.particleDiameter;
    const double layerSpacing = d*std::sqrt(2.0/3.0);
    const int layersPerHalf = 1 + static_cast<int>(std::lround((settings_.halfLength - d)/layerSpacing));
    const PlanPolygon outline = PlanPolygon::regular(settings_.polygonSides, 0.5*settings_.diameter);
    area_ = M_PI*0.25*settings_.diameter*settings_.diameter;
    const double interfaceZ = 0.5*d + (layersPerHalf - 0.5)*layerSpacing;
    for (const Vec3& c : hcpBlockCentres(outline, d, 2*layersPerHalf))
    {
        const int layer = static_cast<int>(std::lround((c.z() - 0.5*d)/layerSpacing));
        ParticleSpec p;
        p.position = c - Vec3(0, 0, interfaceZ);
        p.radius = 0.5*d;
        p.block = layer < layersPerHalf ? 0 : 1;
        p.fixed = layer == 0;
        p.material = layer == 0 ? lowerGripType : layer == 2*layersPerHalf - 1 ? upperGripType : bodyType;
        topGripCount_ += p.material == upperGripType;
        particles_.push_back(p);
    }

    BondBuilder builder(ice_);
    for (const BondPair& b : builder.build(particles_))
    {
        if (b.family == BondFamily::ice)
        {
            iceBonds_.push_back(b);
        }
    }
    const BondStatistics stats = bondStatistics(iceBonds_, static_cast<int>(particles_.size()));
    std::ostringstream msg;
    msg << "Specimen: " << particles_.size() << " particles of " << d*1e3 << " mm in " << 2*layersPerHalf
        << " close-packed layers, " << topGripCount_ << " per grip layer; ice bonds: " << stats.summary();
    log(msg.str());

    const double mass = ice_.material.density*M_PI/6.0*d*d*d;
    contact_ = ContactParameters::of(ice_, d, mass);
    // Room for the freeze-bonds: at most 3 per particle across a close-packed interface.
    const TimeStepLimits limits = timeStepLimits(ice_, 0.5*d, stats.maxBondsPerParticle + 3);
    dt_ = chooseTimeStep(ice_, limits, path("constant/iceProperties"));
}


void FreezeBondTensionScene::startLiggghts()
{
    const double r = 0.5*settings_.particleDiameter;
    const double margin = 0.05;
    if (rank_ == 0)
    {
        std::filesystem::create_directories(path("DEM"));
        writeLiggghtsData
        (
            path("DEM/specimen.data"), "freeze-bond tension specimen written by freezeBondTensionDEM",
            particles_, ice_.material.density,
            Vec3(-0.5*settings_.diameter - margin, -0.5*settings_.diameter - margin, -settings_.halfLength - margin),
            Vec3(0.5*settings_.diameter + margin, 0.5*settings_.diameter + margin,
                 settings_.halfLength + settings_.maxPull + margin),
            3,
            [](const ParticleSpec& p) { return p.material; }
        );
    }
    MPI_Barrier(comm_);
    LiggghtsInstance::reportErrorsFromLog(path("log.liggghts"));
    lmp_ = std::make_unique<LiggghtsInstance>(comm_, path("log.liggghts"));
    const double skin = 0.2*r;
    ScriptVariables variables
    {
        {"dataFile", path("DEM/specimen.data")},
        {"ghostCutoff", exactNumber(bondGhostCutoff(ice_, r, skin))},
        {"neighbourSkin", exactNumber(skin)},
        {"dt", exactNumber(dt_)}
    };
    const ScriptVariables contactVars = contactVariables(contact_);
    variables.insert(variables.end(), contactVars.begin(), contactVars.end());
    defineScriptVariables(*lmp_, variables, path("DEM/variables.generated"), "freezeBondTensionDEM");
    const std::string script = path("DEM/in.freezeBondTension");
    if (!std::filesystem::exists(script))
    {
        throw InputError(script, "(file)", "the LIGGGHTS input script is missing");
    }
    lmp_->runScript(script);
    bonds_ = std::make_unique<IceBondForces>(*lmp_, ice_, contact_.normalStiffness);
    lmp_->command("fix iceBondForces all external pf/callback 1 1");
    bonds_->attach("iceBondForces");
    lmp_->command("run 0");     // property/atom is reset by the first run's set-up
    bonds_->createBonds(particles_, iceBonds_);
    lmp_->command("run 0");
}


double FreezeBondTensionScene::lowerGripForce() const
{
    const LAMMPS_NS::Atom& atom = *lmp_->engine().atom;
    double f = 0.0;
    for (int i = 0; i < atom.nlocal; ++i)
    {
        if (atom.type[i] == lowerGripType)
        {
            f += atom.f[i][2];
        }
    }
    return sumOverRanks(comm_, f);
}


double FreezeBondTensionScene::kineticEnergy() const
{
    const LAMMPS_NS::Atom& atom = *lmp_->engine().atom;
    double e = 0.0;
    for (int i = 0; i < atom.nlocal; ++i)
    {
        for (int k = 0; k < 3; ++k)
        {
            e += 0.5*atom.rmass[i]*atom.v[i][k]*atom.v[i][k];
        }
    }
    return sumOverRanks(comm_, e);
}


void FreezeBondTensionScene::confine()
{
    const double load = settings_.confinementPressure*area_;
    std::ostringstream fix;
    fix << std::setprecision(17) << "fix confine upperGrip addforce 0 0 " << -load/topGripCount_;
    lmp_->command(fix.str());
    const long steps = static_cast<long>(std::ceil(settings_.confinementTime/dt_));
    const long chunk = std::max(1L, steps/10);
    for (long done = 0; done < steps; done += chunk)
    {
        // The first run after a fix is added must set it up (pre yes).
        lmp_->command("run " + std::to_string(chunk) + (done ? " pre no post no" : " post no"));
        steps_ += chunk;
    }
    confinementReaction_ = -lowerGripForce();
    std::ostringstream msg;
    msg << "Confined at " << settings_.confinementPressure*1e-3 << " kPa for " << settings_.confinementTime
        << " s: lower-grip reaction " << confinementReaction_ << " N of " << load << " N applied, kinetic energy "
        << kineticEnergy() << " J";
    log(msg.str());
    if (std::abs(confinementReaction_/load - 1.0) > 0.02)
    {
        throw RunError("the specimen did not come to rest under the confinement (reaction "
            + std::to_string(confinementReaction_) + " N against " + std::to_string(load)
            + " N): raise loading.confinementTime in constant/tensionTestProperties");
    }
}


void FreezeBondTensionScene::freezeBond()
{
    const std::vector<Vec3> positions = allPositionsByTag(*lmp_);
    std::vector<ParticleSpec> now = particles_;
    for (std::size_t k = 0; k < now.size(); ++k)
    {
        now[k].position = positions[k];
    }
    if (strengthModel_.areaCorrectionKind() == FreezeBondStrengthModel::AreaCorrectionKind::interface)
    {
        // The real frozen area is the specimen's cross-section, shared by the DEM bonds across it.
        double bondAreas = 0.0;
        for (const NewFreezeBond& b : freezeBondsAtContacts(now, ice_, strengthModel_, contact_.normalStiffness))
        {
            bondAreas += bondArea(ice_.family(BondFamily::freeze), now[b.pair.i].radius, now[b.pair.j].radius);
        }
        if (bondAreas <= 0.0)
        {
            throw RunError("no contacts across the interface to freeze-bond");
        }
        strengthModel_.setAreaCorrection(area_/bondAreas);
    }
    freezeBonds_ = freezeBondsAtContacts(now, ice_, strengthModel_, contact_.normalStiffness);
    freezeStats_ = freezeBondingStatistics(freezeBonds_, now);

    const BondModel model(ice_.family(BondFamily::freeze), ice_.damping);
    std::vector<BondState> states;
    for (const NewFreezeBond& b : freezeBonds_)
    {
        ParticleState pa, pb;
        pa.position = now[b.pair.i].position;
        pa.radius = now[b.pair.i].radius;
        pb.position = now[b.pair.j].position;
        pb.radius = now[b.pair.j].radius;
        BondState s = model.create(b.pair.i + 1, b.pair.j + 1, pa, pb);
        s.family = BondFamily::freeze;
        s.tensileStrength = b.strength.tensile;
        s.shearStrength = b.strength.shear;
        states.push_back(s);
    }
    bonds_->addBonds(states);
    std::ostringstream msg;
    msg << "Freeze-bonds: " << freezeStats_.bonds << " across the interface, confinement "
        << freezeStats_.meanConfinement*1e-3 << " kPa mean (applied " << settings_.confinementPressure*1e-3
        << "), tensile strength " << freezeStats_.meanTensile*1e-3 << " +- " << freezeStats_.sdTensile*1e-3
        << " kPa on the bond area; " << strengthModel_.summary();
    log(msg.str());
}


void FreezeBondTensionScene::pull()
{
    lmp_->command("unfix confine");
    // Let the unloaded specimen relax before pulling.
    const long relax = static_cast<long>(std::ceil(0.2*settings_.confinementTime/dt_));
    lmp_->command("run " + std::to_string(relax) + " post no");
    steps_ += relax;
    lmp_->command("unfix integrateUpperGrip");
    lmp_->command("velocity upperGrip set 0 0 0");
    lmp_->command("fix pull upperGrip move linear 0 0 " + exactNumber(settings_.pullSpeed));

    const double t0 = lmp_->time();
    const long stepsPerSample =
        std::max(1L, static_cast<long>(settings_.maxPull/settings_.pullSpeed/dt_/settings_.samples));
    bool failed = false;
    for (int s = 0; s <= settings_.samples && !failed; ++s)
    {
        lmp_->command("run " + std::to_string(stepsPerSample) + (s ? " pre no post no" : " post no"));
        steps_ += stepsPerSample;
        const double force = lowerGripForce();
        long intact = 0;
        for (const BondLink& l : bonds_->localLinks())
        {
            intact += l.family == static_cast<int>(BondFamily::freeze);
        }
        intact = sumOverRanks(comm_, intact);
        for (const BreakEvent& e : gatherBreakEvents(comm_, bonds_->takeLocalBreakEvents()))
        {
            breakage_.append(e);
        }
        if (!bonds_->failure().empty())
        {
            throw RunError(bonds_->failure());
        }
        const double pull = settings_.pullSpeed*(lmp_->time() - t0);
        curve_.addRow({lmp_->time(), pull, force, force/area_, double(intact)});
        if (force > peakForce_)
        {
            peakForce_ = force;
            pullAtPeak_ = pull;
        }
        failed = intact == 0 && force < 0.05*peakForce_;
    }
    std::ostringstream msg;
    msg << "Pulled " << curve_.row(curve_.nRows() - 1)[1]*1e3 << " mm: peak " << peakForce_ << " N, strength "
        << peakForce_/area_*1e-3 << " kPa" << (failed ? "" : " (NOT fully separated: raise loading.maxPull)");
    log(msg.str());
}


void FreezeBondTensionScene::writeSummary(double wallSeconds) const
{
    if (rank_ != 0)
    {
        return;
    }
    const std::string dir = path("postProcessing/runs/" + settings_.label);
    std::filesystem::create_directories(dir);
    curve_.write(dir + "/forceDisplacement.csv");
    breakage_.writeHdf5(dir + "/breakage.h5");
    std::vector<double> strengths;
    for (const NewFreezeBond& b : freezeBonds_)
    {
        strengths.push_back(b.strength.tensile);
    }
    JsonObject j;
    j.add("case", "freezeBondTension")
     .add("label", settings_.label)
     .add("confinement_pressure_Pa", settings_.confinementPressure)
     .add("submersion_time_min", settings_.submersionTime)
     .add("model_slope", strengthModel_.slope())
     .add("model_intercept_Pa", strengthModel_.intercept())
     .add("area_correction", strengthModel_.areaCorrection())
     .add("peak_force_N", peakForce_)
     .add("strength_Pa", peakForce_/area_)
     .add("pull_at_peak_m", pullAtPeak_)
     .add("specimen_area_m2", area_)
     .add("freeze_bonds", long(freezeStats_.bonds))
     .add("mean_measured_confinement_Pa", freezeStats_.meanConfinement)
     .add("max_measured_confinement_Pa", freezeStats_.maxConfinement)
     .add("confinement_reaction_N", confinementReaction_)
     .add("bond_tensile_strength_mean_Pa", freezeStats_.meanTensile)
     .add("bond_tensile_strength_sd_Pa", freezeStats_.sdTensile)
     .add("bond_tensile_strengths_Pa", strengths)
     .add("particles", long(particles_.size()))
     .add("bonds", long(iceBonds_.size() + freezeBonds_.size()))
     .add("steps", steps_)
     .add("dt", dt_)
     .add("ranks", long(ranks_))
     .add("wall_s", wallSeconds);
    writeFileAtomically(dir + "/summary.json", j.text() + "\n");
}


void FreezeBondTensionScene::run()
{
    const auto start = std::chrono::steady_clock::now();
    buildSpecimen();
    startLiggghts();
    confine();
    freezeBond();
    pull();
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    writeSummary(wall);
    log("Wall time " + formatDuration(wall) + "; results in postProcessing/runs/" + settings_.label);
}

} // namespace iceDEM
