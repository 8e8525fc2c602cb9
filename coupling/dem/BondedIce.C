#include "BondedIce.H"

#include "ContactParameters.H"
#include "FpeTrapsOff.H"
#include "IceBondForces.H"
#include "InputError.H"
#include "LiggghtsInstance.H"
#include "ParticleGather.H"
#include "SceneSetup.H"
#include "TimeStep.H"

#include "atom.h"
#include "force.h"
#include "lammps.h"
#include "neighbor.h"

#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <sstream>

namespace iceCoupling
{

namespace
{

constexpr const char* bondFixId = "iceBondForces";

//- One value for every pair of atom types, for `peratomtypepair`.
std::string everyTypePair(int types, double value)
{
    std::string values;
    for (int k = 0; k < types*types; ++k)
    {
        values += " " + iceDEM::exactNumber(value);
    }
    return values;
}

std::string tenDigits(double value)
{
    std::ostringstream s;
    s << std::setprecision(10) << value;
    return s.str();
}

} // namespace


BondedIce::BondedIce
(
    iceDEM::LiggghtsInstance& lmp,
    const std::string& icePropertiesPath,
    const std::string& demScriptPath,
    const std::vector<CouplingParticle>& particles
)
:
    lmp_(lmp),
    icePropertiesPath_(icePropertiesPath),
    demScriptPath_(demScriptPath),
    ice_(iceDEM::IceProperties::read(icePropertiesPath))
{
    if (lmp_.engine().force->pair)
    {
        throw iceDEM::InputError(demScriptPath_, "pair_style",
            "must not be set when constant/iceProperties is present: the contact law must match the"
            " bonds (physics.md section 3), so iceFoam defines it from iceProperties");
    }
    std::vector<iceDEM::ParticleSpec> specs;
    specs.reserve(particles.size());
    double diameterSum = 0.0, minMass = HUGE_VAL, minRadius = HUGE_VAL, maxRadius = 0.0;
    for (std::size_t k = 0; k < particles.size(); ++k)
    {
        const CouplingParticle& p = particles[k];
        if (p.tag != static_cast<long>(k) + 1)
        {
            throw iceDEM::InputError(demScriptPath_, "(atoms)",
                "the bonded ice model needs atom tags 1..N without gaps (tag "
                + std::to_string(p.tag) + " at position " + std::to_string(k + 1) + ")");
        }
        const double r = 0.5*p.diameter;
        const double density = p.mass/(4.0/3.0*M_PI*r*r*r);
        if (std::abs(density/ice_.material.density - 1.0) > 1e-6)
        {
            throw iceDEM::InputError(demScriptPath_, "density",
                "atom " + std::to_string(p.tag) + " has " + tenDigits(density)
                + " kg/m3; constant/iceProperties material.density is " + tenDigits(ice_.material.density));
        }
        iceDEM::ParticleSpec spec;
        spec.position = iceDEM::Vec3(p.position[0], p.position[1], p.position[2]);
        spec.radius = r;
        specs.push_back(spec);
        diameterSum += p.diameter;
        minMass = std::min(minMass, p.mass);
        minRadius = std::min(minRadius, r);
        maxRadius = std::max(maxRadius, r);
    }
    if (specs.size() < 2)
    {
        throw iceDEM::InputError(demScriptPath_, "(atoms)", "the bonded ice model needs at least two particles");
    }

    iceDEM::BondBuilder builder(ice_);
    const std::vector<iceDEM::BondPair> pairs = builder.build(specs);
    statistics_ = builder.statistics();
    checkTimeStep(minRadius);
    defineContacts(diameterSum/specs.size(), minMass, maxRadius);

    bonds_ = iceDEM::IceBondForces::define(lmp_, ice_, bondFixId);
    const FpeTrapsOff untrapped;
    lmp_.command("run 0");   // LIGGGHTS' first set-up resets property/atom values
    bonds_->createBonds(specs, pairs);
    lmp_.command("run 0");

    int rank = 0;
    MPI_Comm_rank(lmp_.communicator(), &rank);
    if (rank == 0)
    {
        std::cout << "Bonded ice (" << icePropertiesPath_ << "): " << statistics_.summary() << std::endl;
    }
}


BondedIce::~BondedIce() = default;


void BondedIce::checkTimeStep(double minRadius) const
{
    const iceDEM::TimeStepLimits limits =
        iceDEM::timeStepLimits(ice_, minRadius, statistics_.maxBondsPerParticle);
    if (lmp_.timeStep() > limits.limit)
    {
        throw iceDEM::InputError(demScriptPath_, "timestep",
            iceDEM::exactNumber(lmp_.timeStep()) + " s is above the bonded pack's stability limit "
            + iceDEM::exactNumber(limits.limit) + " s (stiffest spring: " + limits.stiffestSpringName
            + "; recommended " + iceDEM::exactNumber(limits.recommended) + " s)");
    }
}


void BondedIce::defineContacts(double meanDiameter, double minMass, double maxRadius)
{
    const iceDEM::ContactParameters c = iceDEM::ContactParameters::of(ice_, meanDiameter, minMass);
    const int types = lmp_.engine().atom->ntypes;
    const std::pair<const char*, double> properties[] =
    {
        {"kn", c.normalStiffness}, {"kt", c.tangentialStiffness},
        {"gamman_abs", c.normalDamping}, {"gammat_abs", c.tangentialDamping},
        {"coefficientFriction", c.friction}, {"coefficientRollingFriction", c.rollingFriction}
    };
    for (const auto& [name, value] : properties)
    {
        lmp_.command(std::string("fix iceContact_") + name + " all property/global " + name
            + " peratomtypepair " + std::to_string(types) + everyTypePair(types, value));
    }
    lmp_.command("pair_style gran model hooke/stiffness tangential history rolling_friction epsd2"
                 " absolute_damping on");
    lmp_.command("pair_coeff * *");
    // Ghost atoms must hold every bonded partner, with room for the bond to stretch.
    const double skin = lmp_.engine().neighbor->skin;
    lmp_.command("communicate single cutoff " + iceDEM::exactNumber(iceDEM::bondGhostCutoff(ice_, maxRadius, skin))
                 + " vel yes");
}


void BondedIce::collectBreaks(double time)
{
    const std::string& failure = bonds_->failure();
    int failed = failure.empty() ? 0 : 1, anyFailed = 0;
    MPI_Allreduce(&failed, &anyFailed, 1, MPI_INT, MPI_MAX, lmp_.communicator());
    if (anyFailed)
    {
        throw iceDEM::RunError(failure.empty() ? "the bonded ice model failed on another rank" : failure);
    }
    const long local = static_cast<long>(bonds_->takeLocalBreakEvents().size());
    broken_ += iceDEM::sumOverRanks(lmp_.communicator(), local);
    history_.addRow({time, static_cast<double>(intactBonds()), static_cast<double>(broken_)});
}


void BondedIce::writeHistory(const std::string& path) const
{
    int rank = 0;
    MPI_Comm_rank(lmp_.communicator(), &rank);
    if (rank == 0)
    {
        history_.write(path);
    }
}


long BondedIce::intactBonds() const
{
    return iceDEM::sumOverRanks(lmp_.communicator(), static_cast<long>(bonds_->localLinks().size()));
}

} // namespace iceCoupling
