#include "IceBondForces.H"

#include "BondBuilder.H"
#include "HystereticDamping.H"
#include "InputError.H"
#include "LiggghtsInstance.H"

#include "atom.h"
#include "fix_external.h"
#include "lammps.h"
#include "update.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace iceDEM
{

namespace
{

Vec3 row(double** a, int i)
{
    return Vec3(a[i][0], a[i][1], a[i][2]);
}


} // namespace


void BondLoadSums::reset(int atoms, int capacity)
{
    capacity_ = capacity;
    count_.assign(atoms, 0);
    entries_.resize(static_cast<std::size_t>(atoms) * capacity);
}


void BondLoadSums::add(int atom, long partnerTag, const Vec3& force, const Vec3& torque)
{
    entries_[static_cast<std::size_t>(atom) * capacity_ + count_[atom]++] = {partnerTag, force, torque};
}


void BondLoadSums::addSumTo(int atom, double* force, double* torque)
{
    Entry* first = &entries_[static_cast<std::size_t>(atom) * capacity_];
    Entry* last = first + count_[atom];
    std::sort(first, last, [](const Entry& x, const Entry& y) { return x.partnerTag < y.partnerTag; });
    for (const Entry* e = first; e != last; ++e)
    {
        for (int k = 0; k < 3; ++k)
        {
            force[k] += e->force[k];
            torque[k] += e->torque[k];
        }
    }
}


IceBondForces::IceBondForces
(
    LiggghtsInstance& lmp,
    const IceProperties& props,
    double contactNormalStiffness
)
:
    lmp_(lmp),
    models_
    {
        BondModel(props.family(BondFamily::ice), props.damping),
        BondModel(props.family(BondFamily::freeze), props.damping)
    },
    damping_(props.damping),
    contactNormalStiffness_(contactNormalStiffness),
    table_(lmp, props.maxBondsPerParticle)
{}


ParticleState IceBondForces::particle(int i) const
{
    const LAMMPS_NS::Atom& atom = *lmp_.engine().atom;
    ParticleState p;
    p.position = row(atom.x, i);
    p.velocity = row(atom.v, i);
    p.angularVelocity = row(atom.omega, i);
    p.radius = atom.radius[i];
    p.mass = atom.rmass[i];
    return p;
}


void IceBondForces::createBonds
(
    const std::vector<ParticleSpec>& particles,
    const std::vector<BondPair>& pairs
)
{
    auto spec = [&](int index)
    {
        ParticleState p;
        p.position = particles[index].position;
        p.radius = particles[index].radius;
        return p;
    };
    std::vector<BondState> states;
    states.reserve(pairs.size());
    for (const BondPair& pair : pairs)
    {
        BondState state =
            models_[static_cast<int>(pair.family)].create(pair.i + 1, pair.j + 1, spec(pair.i), spec(pair.j));
        state.family = pair.family;
        states.push_back(state);
    }
    for (const BondState& state : states)
    {
        store(state);
    }
}


void IceBondForces::restoreBonds(const std::vector<BondState>& states)
{
    for (int i = 0; i < lmp_.engine().atom->nlocal; ++i)
    {
        table_.clear(i);
    }
    for (const BondState& state : states)
    {
        store(state);
    }
}


void IceBondForces::addBonds(const std::vector<BondState>& states)
{
    for (const BondState& state : states)
    {
        store(state);
    }
}


void IceBondForces::store(const BondState& state)
{
    LAMMPS_NS::Atom& atom = *lmp_.engine().atom;
    for (long own : {state.tagA, state.tagB})
    {
        const int local = atom.map(static_cast<int>(own));
        if (local < 0 || local >= atom.nlocal)
        {
            continue;
        }
        if (!table_.add(local, state, own))
        {
            std::ostringstream msg;
            msg << "particle " << own << " needs more than " << table_.capacity()
                << " bonds; raise maxBondsPerParticle or lower distFactor";
            throw InputError("constant/iceProperties", "maxBondsPerParticle", msg.str());
        }
    }
}


std::vector<BondState> IceBondForces::localBondStates() const
{
    const LAMMPS_NS::Atom& atom = *lmp_.engine().atom;
    std::vector<BondState> states;
    for (int i = 0; i < atom.nlocal; ++i)
    {
        const int n = table_.count(i);
        for (int slot = 0; slot < n; ++slot)
        {
            if (atom.tag[i] < table_.partner(i, slot))
            {
                states.push_back(table_.read(i, slot, atom.tag[i]));
            }
        }
    }
    return states;
}


void IceBondForces::attach(const std::string& fixExternalId)
{
    auto& fix = static_cast<LAMMPS_NS::FixExternal&>(lmp_.fix(fixExternalId));
    fix.set_callback(&IceBondForces::callback, this);
}


void IceBondForces::callback(void* self, int64_t, int nlocal, int*, double**, double** fexternal)
{
    // We write forces and torques straight into LIGGGHTS' arrays; the fix's
    // own force array must add nothing.
    for (int i = 0; i < nlocal; ++i)
    {
        fexternal[i][0] = fexternal[i][1] = fexternal[i][2] = 0.0;
    }
    static_cast<IceBondForces*>(self)->compute();
}


void IceBondForces::fail(const std::string& what)
{
    if (failure_.empty())
    {
        std::ostringstream msg;
        msg << what << " (step " << lmp_.step() << ", time " << lmp_.time() << " s)";
        failure_ = msg.str();
    }
}


void IceBondForces::compute()
{
    LAMMPS_NS::Atom& atom = *lmp_.engine().atom;
    const int nlocal = atom.nlocal;
    const int* tag = atom.tag;
    const double dt = lmp_.timeStep();
    const double time = lmp_.time();
    loads_.reset(nlocal, table_.capacity());

    for (int i = 0; i < nlocal; ++i)
    {
        int n = table_.count(i);
        for (int slot = 0; slot < n;)
        {
            const long partnerTag = table_.partner(i, slot);
            const int j = atom.map(static_cast<int>(partnerTag));
            if (j < 0)
            {
                std::ostringstream msg;
                msg << "bond partner " << partnerTag << " of particle " << tag[i]
                    << " at (" << row(atom.x, i).transpose() << ") is not within this rank's"
                    << " ghost cut-off: the bond has stretched too far, or the partner left the simulation box";
                fail(msg.str());
                ++slot;
                continue;
            }
            const bool partnerLocal = j < nlocal;
            if (partnerLocal && tag[i] > partnerTag)
            {
                ++slot;   // evaluated from the partner, which has the lower tag
                continue;
            }

            BondState state = table_.read(i, slot, tag[i]);
            const bool iIsA = tag[i] < partnerTag;
            const int a = iIsA ? i : j;
            const int b = iIsA ? j : i;
            const ParticleState pa = particle(a);
            const ParticleState pb = particle(b);
            const BondLoad load = models_[static_cast<int>(state.family)].evaluate(state, pa, pb, dt);
            const int partnerSlot = partnerLocal ? table_.find(j, tag[i]) : -1;

            if (load.broke != BreakMode::none)
            {
                if (a < nlocal)
                {
                    breaks_.push_back({time, load.centre, state.tagA, state.tagB, state.family, load.broke});
                }
                table_.remove(i, slot);
                if (partnerSlot >= 0)
                {
                    table_.remove(j, partnerSlot);
                }
                --n;
                continue;
            }

            Vec3 forceOnA = load.forceOnA;
            const Vec3 separation = pb.position - pa.position;
            const double overlap = pa.radius + pb.radius - separation.norm();
            if (overlap > 0.0)
            {
                // Cancel the contact's normal spring: a bonded pair has the bond only.
                forceOnA += contactNormalStiffness_ * overlap * separation.normalized();
            }

            if (a < nlocal)
            {
                loads_.add(a, state.tagB, forceOnA, load.torqueOnA);
            }
            if (b < nlocal)
            {
                loads_.add(b, state.tagA, -forceOnA, load.torqueOnB);
            }
            table_.write(i, slot, state, tag[i]);
            if (partnerSlot >= 0)
            {
                table_.write(j, partnerSlot, state, partnerTag);
            }
            ++slot;
        }
    }

    const bool hysteretic = damping_.model == DampingModel::hysteretic && damping_.alpha > 0.0;
    for (int i = 0; i < nlocal; ++i)
    {
        loads_.addSumTo(i, atom.f[i], atom.torque[i]);
        Vec3 force = row(atom.f, i);
        Vec3 torque = row(atom.torque, i);
        if (!std::isfinite(force.squaredNorm()) || !std::isfinite(torque.squaredNorm()))
        {
            std::ostringstream msg;
            msg << "non-finite force on particle " << tag[i] << " at (" << row(atom.x, i).transpose()
                << "): the run has blown up";
            fail(msg.str());
            continue;
        }
        if (hysteretic)
        {
            applyHystereticDamping(force, row(atom.v, i), damping_.alpha);
            applyHystereticDamping(torque, row(atom.omega, i), damping_.alpha);
            for (int k = 0; k < 3; ++k)
            {
                atom.f[i][k] = force[k];
                atom.torque[i][k] = torque[k];
            }
        }
    }
}


std::vector<BreakEvent> IceBondForces::takeLocalBreakEvents()
{
    std::vector<BreakEvent> taken;
    taken.swap(breaks_);
    return taken;
}


std::vector<BondLink> IceBondForces::localLinks() const
{
    std::vector<BondLink> links;
    for (const BondState& s : localBondStates())
    {
        links.push_back({s.tagA, s.tagB, static_cast<int>(s.family)});
    }
    return links;
}


double IceBondForces::localBondEnergy() const
{
    LAMMPS_NS::Atom& atom = *lmp_.engine().atom;   // map() is not const
    double energy = 0.0;
    for (int i = 0; i < atom.nlocal; ++i)
    {
        const int n = table_.count(i);
        for (int slot = 0; slot < n; ++slot)
        {
            const long partnerTag = table_.partner(i, slot);
            const int j = atom.map(static_cast<int>(partnerTag));
            if (atom.tag[i] < partnerTag && j >= 0)
            {
                const BondState s = table_.read(i, slot, atom.tag[i]);
                energy += models_[static_cast<int>(s.family)].potentialEnergy(s, particle(i), particle(j));
            }
        }
    }
    return energy;
}

} // namespace iceDEM
