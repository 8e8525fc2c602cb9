#include "FreezeBondSpecimen.H"

#include "BondBuilder.H"
#include "BondModel.H"
#include "Dictionary.H"
#include "IceBlocks.H"
#include "IceBondForces.H"
#include "FreezeBonding.H"
#include "InterfaceAreaCorrection.H"
#include "InputError.H"
#include "LiggghtsInstance.H"
#include "ParticleGather.H"
#include "TimeStep.H"

#include "atom.h"
#include "lammps.h"

#include <cmath>
#include <filesystem>
#include <iostream>
#include <sstream>

namespace iceDEM
{



SpecimenGeometry SpecimenGeometry::read(const Dictionary& sp, const SpecimenGeometry& defaults)
{
    sp.checkKeys({"diameter", "halfLength", "particleDiameter", "polygonSides"});
    SpecimenGeometry g = defaults;
    g.diameter = sp.getPositiveScalarOrDefault("diameter", g.diameter);
    g.halfLength = sp.getPositiveScalarOrDefault("halfLength", g.halfLength);
    g.particleDiameter = sp.getPositiveScalarOrDefault("particleDiameter", g.particleDiameter);
    g.polygonSides = sp.getLabelOrDefault("polygonSides", g.polygonSides);
    if (g.polygonSides < 6) sp.fail("polygonSides", "must be at least 6");
    if (g.particleDiameter*4 > g.diameter) sp.fail("particleDiameter", "must be at most a quarter of the diameter");
    if (g.particleDiameter*3 > g.halfLength) sp.fail("particleDiameter", "must be at most a third of halfLength");
    return g;
}


FreezeBondSpecimen::FreezeBondSpecimen
(
    MPI_Comm comm,
    const std::string& caseDir,
    const std::string& appName,
    double submersionTime
)
:
    context_(comm, caseDir, appName)
{
    ice_ = IceProperties::read(context_.path("constant/iceProperties"));
    requireFreezeBondStrengthsPerBond(ice_, context_.path("constant/iceProperties"));
    freezeBondProperties_ = FreezeBondProperties::read(context_.path("constant/freezeBondProperties"));
    freezeBondProperties_.checkIce(ice_, context_.path("constant/iceProperties"));
    if (submersionTime > 0.0)
    {
        freezeBondProperties_.setSubmersionTime(submersionTime);
    }
}


FreezeBondSpecimen::~FreezeBondSpecimen() = default;


void FreezeBondSpecimen::setFreezeModulus(double youngsModulus)
{
    ice_.families[static_cast<int>(BondFamily::freeze)].youngsModulus = youngsModulus;
}




double FreezeBondSpecimen::layerHeight(int layer) const
{
    return (layer - layersPerHalf_ + 0.5)*layerSpacing_;
}


void FreezeBondSpecimen::build
(
    const SpecimenGeometry& geometry,
    int atomTypes,
    const std::function<int(int layer, const ParticleSpec&)>& typeOf
)
{
    geometry_ = geometry;
    atomTypes_ = atomTypes;
    const double d = geometry.particleDiameter;
    layerSpacing_ = d*std::sqrt(2.0/3.0);
    layersPerHalf_ = 1 + static_cast<int>(std::lround((geometry.halfLength - d)/layerSpacing_));
    const PlanPolygon outline = PlanPolygon::regular(geometry.polygonSides, 0.5*geometry.diameter);
    const double interfaceZ = 0.5*d + (layersPerHalf_ - 0.5)*layerSpacing_;
    for (const Vec3& c : hcpBlockCentres(outline, d, 2*layersPerHalf_))
    {
        const int layer = static_cast<int>(std::lround((c.z() - 0.5*d)/layerSpacing_));
        ParticleSpec p;
        p.position = c - Vec3(0, 0, interfaceZ);
        p.radius = 0.5*d;
        p.block = layer < layersPerHalf_ ? 0 : 1;
        p.material = typeOf(layer, p);
        if (p.material < 1 || p.material > atomTypes)
        {
            throw std::logic_error("FreezeBondSpecimen::build: atom type out of range");
        }
        particles_.push_back(p);
        layerOf_.push_back(layer);
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
    msg << "Specimen: " << particles_.size() << " particles of " << d*1e3 << " mm in " << 2*layersPerHalf_
        << " close-packed layers; ice bonds: " << stats.summary();
    context_.log(msg.str());

    contact_ = ContactParameters::of(ice_, d, ice_.material.density*M_PI/6.0*d*d*d);
    // Room for the freeze-bonds: at most 3 per particle across a close-packed interface.
    const TimeStepLimits limits = timeStepLimits(ice_, 0.5*d, stats.maxBondsPerParticle + 3);
    dt_ = chooseTimeStep(ice_, limits, context_.path("constant/iceProperties"));
}


void FreezeBondSpecimen::start(const std::string& script, const ScriptVariables& extra, double margin)
{
    const double r = 0.5*geometry_.particleDiameter;
    const double reach = 0.5*geometry_.diameter + margin;
    if (context_.rank() == 0)
    {
        std::filesystem::create_directories(context_.path("DEM"));
        writeLiggghtsData
        (
            context_.path("DEM/specimen.data"), "freeze-bond specimen written by " + context_.application(),
            particles_, ice_.material.density,
            Vec3(-reach, -reach, -geometry_.halfLength - margin),
            Vec3(reach, reach, geometry_.halfLength + margin),
            atomTypes_,
            [](const ParticleSpec& p) { return p.material; }
        );
    }
    MPI_Barrier(context_.comm());
    const double skin = 0.2*r;
    ScriptVariables variables
    {
        {"dataFile", context_.path("DEM/specimen.data")},
        {"ghostCutoff", exactNumber(bondGhostCutoff(ice_, r, skin))},
        {"neighbourSkin", exactNumber(skin)},
        {"dt", exactNumber(dt_)}
    };
    const ScriptVariables contactVars = contactVariables(contact_);
    variables.insert(variables.end(), contactVars.begin(), contactVars.end());
    variables.insert(variables.end(), extra.begin(), extra.end());
    lmp_ = context_.startLiggghts(variables, "DEM/" + script);
    bonds_ = IceBondForces::define(*lmp_, ice_);
    lmp_->command("run 0");     // property/atom is reset by the first run's set-up
    bonds_->createBonds(particles_, iceBonds_);
    lmp_->command("run 0");
}


void FreezeBondSpecimen::run(long steps)
{
    lmp_->command("run " + std::to_string(steps) + (setUpNextRun_ ? " post no" : " pre no post no"));
    setUpNextRun_ = false;
    steps_ += steps;
}


double FreezeBondSpecimen::time() const
{
    return lmp_->time();
}


double FreezeBondSpecimen::forceOnType(int type, int component) const
{
    const LAMMPS_NS::Atom& atom = *lmp_->engine().atom;
    double f = 0.0;
    for (int i = 0; i < atom.nlocal; ++i)
    {
        if (atom.type[i] == type)
        {
            f += atom.f[i][component];
        }
    }
    return sumOverRanks(context_.comm(), f);
}


long FreezeBondSpecimen::atomsOfType(int type) const
{
    long n = 0;
    for (const ParticleSpec& p : particles_)
    {
        n += p.material == type;
    }
    return n;
}


double FreezeBondSpecimen::meanPositionOfLayer(int layer, int component) const
{
    const LAMMPS_NS::Atom& atom = *lmp_->engine().atom;
    double sum = 0.0;
    long n = 0;
    for (int i = 0; i < atom.nlocal; ++i)
    {
        if (layerOf_[atom.tag[i] - 1] == layer)
        {
            sum += atom.x[i][component];
            ++n;
        }
    }
    return sumOverRanks(context_.comm(), sum)/static_cast<double>(sumOverRanks(context_.comm(), n));
}


void FreezeBondSpecimen::freezeBond(double interfaceArea)
{
    const std::vector<Vec3> positions = allPositionsByTag(*lmp_);
    std::vector<ParticleSpec> now = particles_;
    for (std::size_t k = 0; k < now.size(); ++k)
    {
        now[k].position = positions[k];
    }
    freezeBonds_ = freezeBondsAtContacts(now, ice_, freezeBondProperties_, contact_.normalStiffness);
    if
    (
        auto* interfaceCorrection =
            dynamic_cast<InterfaceAreaCorrection*>(&freezeBondProperties_.areaCorrection())
    )
    {
        // The real frozen area is the specimen's cross-section, shared by the DEM bonds across
        // it: c_f is known once the bonds are, and their strengths follow from it.
        const BondFamilyParameters& family = ice_.family(BondFamily::freeze);
        double bondAreas = 0.0;
        for (const NewFreezeBond& b : freezeBonds_)
        {
            bondAreas += bondArea(family, now[b.pair.i].radius, now[b.pair.j].radius);
        }
        if (bondAreas <= 0.0)
        {
            throw RunError("no contacts across the interface to freeze-bond");
        }
        interfaceCorrection->setFromInterface(interfaceArea, bondAreas);
        for (NewFreezeBond& b : freezeBonds_)
        {
            b.strength = freezeBondProperties_.strength
            (
                b.contactForce, bondArea(family, now[b.pair.i].radius, now[b.pair.j].radius)
            );
        }
    }
    freezeStats_ = freezeBondingStatistics(freezeBonds_, now);
    bonds_->addBonds(freezeBondStates(freezeBonds_, now, ice_));
    std::ostringstream msg;
    msg << "Freeze-bonds: " << freezeStats_.bonds << " across the interface, confinement "
        << freezeStats_.meanConfinement*1e-3 << " kPa mean, tensile strength " << freezeStats_.meanTensile*1e-3
        << " +- " << freezeStats_.sdTensile*1e-3 << " kPa, shear " << freezeStats_.meanShear*1e-3
        << " kPa on the bond area; " << freezeBondProperties_.summary();
    context_.log(msg.str());
}


std::string FreezeBondSpecimen::writeRunRecord(const std::string& label) const
{
    const std::string dir = context_.path("postProcessing/runs/" + label);
    std::filesystem::create_directories(dir);
    breakage_.writeHdf5(dir + "/breakage.h5");
    return dir;
}


void FreezeBondSpecimen::addRunFigures(Json& j, double wallSeconds) const
{
    j["particles"] = long(particles_.size());
    j["bonds"] = long(iceBonds_.size() + freezeBonds_.size());
    j["steps"] = steps_;
    j["dt"] = dt_;
    j["ranks"] = long(context_.ranks());
    j["wall_s"] = wallSeconds;
}


double FreezeBondSpecimen::freezeBondArea() const
{
    double area = 0.0;
    for (const NewFreezeBond& b : freezeBonds_)
    {
        area += bondArea(ice_.family(BondFamily::freeze), particles_[b.pair.i].radius, particles_[b.pair.j].radius);
    }
    return area;
}


long FreezeBondSpecimen::intactFreezeBonds() const
{
    long intact = 0;
    for (const BondLink& l : bonds_->localLinks())
    {
        intact += l.family == static_cast<int>(BondFamily::freeze);
    }
    return sumOverRanks(context_.comm(), intact);
}


void FreezeBondSpecimen::collectBreaks()
{
    for (const BreakEvent& e : gatherBreakEvents(context_.comm(), bonds_->takeLocalBreakEvents()))
    {
        breakage_.append(e);
    }
}


void FreezeBondSpecimen::checkHealth() const
{
    if (!bonds_->failure().empty())
    {
        throw RunError(bonds_->failure());
    }
}

} // namespace iceDEM
