#include "IceBondForces.H"

#include "BondBuilder.H"
#include "HystereticDamping.H"
#include "InputError.H"
#include "LiggghtsInstance.H"

#include "atom.h"
#include "fix.h"
#include "fix_external.h"
#include "force.h"
#include "lammps.h"
#include "lmptype.h"
#include "modify.h"
#include "neigh_list.h"
#include "neighbor.h"
#include "pair_gran.h"
#include "update.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <tuple>

namespace iceDEM
{

namespace
{

Vec3 row(double** a, int i)
{
    return Vec3(a[i][0], a[i][1], a[i][2]);
}


} // namespace


//- IceBondForces' hooks into LIGGGHTS' step, which has no input-script
//  style for them (IceBondForces::attach puts this fix in a placeholder's
//  place):
//  - before LIGGGHTS moves atoms (between ranks, or re-sorting them on one)
//    or writes a restart file, the per-atom table must hold every history;
//  - after each neighbour-list build, bonded pairs leave the granular contact
//    list: a bonded pair interacts through its bond alone (physics.md section 2);
//  - a bond that broke this step lets its pair back into the contact list by
//    a rebuild at the next step (requested on every rank alike: a rebuild
//    moves atoms between ranks).
class IceBondHooks : public LAMMPS_NS::Fix
{
public:
    IceBondHooks(LAMMPS_NS::LAMMPS* engine, char** args, std::shared_ptr<IceBondForces*> target)
    :
        Fix(engine, 3, args),
        target_(std::move(target))
    {
        force_reneighbor = 1;
        next_reneighbor = -1;
    }

    void retarget(std::shared_ptr<IceBondForces*> target) { target_ = std::move(target); }

    int setmask() override { return LAMMPS_NS::FixConst::PRE_EXCHANGE | LAMMPS_NS::FixConst::PRE_FORCE; }
    void setup_pre_exchange() override { syncTable(); }
    void pre_exchange() override { syncTable(); }
    void setup_pre_force(int) override { removeBondedPairs(); }
    void pre_force(int) override
    {
        if (neighbor->ago == 0 || (*target_ && (*target_)->contactListIsStale()))
        {
            removeBondedPairs();
        }
    }

    void rebuildNeighboursAtNextStep() { next_reneighbor = update->ntimestep + 1; }

private:
    void syncTable()
    {
        if (*target_)
        {
            (*target_)->syncTable();
        }
    }

    void removeBondedPairs()
    {
        if (*target_)
        {
            (*target_)->removeBondedPairsFromContacts();
        }
    }

    // Null once the IceBondForces is destroyed (LIGGGHTS may outlive it).
    std::shared_ptr<IceBondForces*> target_;
};


std::array<BondModel, nBondFamilies> IceBondForces::modelsOf(const IceProperties& props)
{
    return
    {
        BondModel(props.family(BondFamily::ice), props.damping),
        BondModel(props.family(BondFamily::freeze), props.damping)
    };
}


IceBondForces::IceBondForces(LiggghtsInstance& lmp, const IceProperties& props)
:
    lmp_(lmp),
    models_(modelsOf(props)),
    ice_(props),
    table_(lmp, props.maxBondsPerParticle)
{}


IceBondForces::~IceBondForces()
{
    if (hooksTarget_)
    {
        *hooksTarget_ = nullptr;
    }
}


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
    const std::vector<BondState> states = newBondStates(pairs, particles, ice_);
    syncTable();
    for (const BondState& state : states)
    {
        store(state);
    }
    contactListIsStale_ = true;
}


void IceBondForces::restoreBonds(const std::vector<BondState>& states)
{
    listIsCurrent_ = false;
    for (int i = 0; i < lmp_.engine().atom->nlocal; ++i)
    {
        table_.clear(i);
    }
    for (const BondState& state : states)
    {
        store(state);
    }
    contactListIsStale_ = true;
}


void IceBondForces::addBonds(const std::vector<BondState>& states)
{
    syncTable();    // the running histories go back to the table before it changes
    for (const BondState& state : states)
    {
        store(state);
    }
    contactListIsStale_ = true;
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


BondTable& IceBondForces::table()
{
    syncTable();
    return table_;
}


void IceBondForces::syncTable()
{
    if (!listIsCurrent_)
    {
        return;
    }
    const int nlocal = lmp_.engine().atom->nlocal;
    for (std::size_t k = 0; k < list_.size(); ++k)
    {
        if (!intact_[k])
        {
            continue;   // already gone from the table
        }
        const BondState state = listedState(k);
        for (const auto& [own, other, atom] :
            {std::tuple(state.tagA, state.tagB, atomOf_[list_[k].a]),
             std::tuple(state.tagB, state.tagA, atomOf_[list_[k].b])})
        {
            if (atom < nlocal)
            {
                table_.write(atom, table_.find(atom, other), state, own);
            }
        }
    }
    listIsCurrent_ = false;
}

void IceBondForces::rebuildList()
{
    LAMMPS_NS::Atom& atom = *lmp_.engine().atom;
    const int nlocal = atom.nlocal;
    const int* tag = atom.tag;

    // The bonds, each once, with LIGGGHTS' indices of their atoms for now.
    list_.clear();
    for (int i = 0; i < nlocal; ++i)
    {
        const int n = table_.count(i);
        for (int slot = 0; slot < n; ++slot)
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
                continue;
            }
            if (j < nlocal && tag[i] > partnerTag)
            {
                continue;   // listed from the partner, which has the lower tag
            }
            ListedBond bond;
            bond.state = table_.read(i, slot, tag[i]);
            const bool iIsA = tag[i] < partnerTag;
            bond.a = iIsA ? i : j;
            bond.b = iIsA ? j : i;
            list_.push_back(bond);
        }
    }

    // The local atoms in LIGGGHTS' order, which is spatial (it sorts atoms
    // in bins at each run's set-up and every 1000 steps), then the bonded ghosts.
    std::vector<int> entryOf(nlocal + atom.nghost, -1);
    atomOf_.clear();
    for (int i = 0; i < nlocal; ++i)
    {
        entryOf[i] = 0;
        atomOf_.push_back(i);
    }
    for (const ListedBond& bond : list_)
    {
        for (int end : {bond.a, bond.b})
        {
            if (entryOf[end] < 0)
            {
                entryOf[end] = 0;
                atomOf_.push_back(end);
            }
        }
    }
    particles_.resize(atomOf_.size());
    for (std::size_t e = 0; e < atomOf_.size(); ++e)
    {
        entryOf[atomOf_[e]] = static_cast<int>(e);
        particles_[e].radius = atom.radius[atomOf_[e]];
        particles_[e].mass = atom.rmass[atomOf_[e]];
    }

    std::map<std::tuple<int, double, double>, int> stiffnessIndex;
    stiffnesses_.clear();
    for (ListedBond& bond : list_)
    {
        bond.a = entryOf[bond.a];
        bond.b = entryOf[bond.b];
        const int family = static_cast<int>(bond.state.family);
        const double radiusA = particles_[bond.a].radius;
        const double radiusB = particles_[bond.b].radius;
        const auto known = stiffnessIndex.find({family, radiusA, radiusB});
        if (known != stiffnessIndex.end())
        {
            bond.stiffness = known->second;
            continue;
        }
        bond.stiffness = static_cast<int>(stiffnesses_.size());
        stiffnessIndex.emplace(std::make_tuple(family, radiusA, radiusB), bond.stiffness);
        stiffnesses_.push_back(BondStiffness::of(models_[family].parameters(), radiusA, radiusB));
    }
    std::sort(list_.begin(), list_.end(), [](const ListedBond& x, const ListedBond& y)
    {
        return std::tie(x.a, x.b) < std::tie(y.a, y.b);
    });
    intact_.assign(list_.size(), 1);
    batches_.resize(list_.size());
    for (std::size_t k = 0; k < list_.size(); ++k)
    {
        const ListedBond& bond = list_[k];
        const BondStiffness& stiffness = stiffnesses_[bond.stiffness];
        const BondModel& model = models_[static_cast<int>(bond.state.family)];
        batches_.set(k, bond.a, bond.b, bond.state, stiffness, model.intactBounds(bond.state, stiffness));
    }
    batches_.pad();

    // Each local atom's load slots, by partner tag.
    const int entries = static_cast<int>(atomOf_.size());
    firstOfAtom_.assign(entries + 1, 0);
    for (const ListedBond& bond : list_)
    {
        for (int end : {bond.a, bond.b})
        {
            if (atomOf_[end] < nlocal)
            {
                ++firstOfAtom_[end + 1];
            }
        }
    }
    for (int e = 0; e < entries; ++e)
    {
        firstOfAtom_[e + 1] += firstOfAtom_[e];
    }
    std::vector<int> atomBonds(firstOfAtom_[entries]);   // 2 * listed bond (+1 where the atom is b)
    std::vector<int> next(firstOfAtom_.begin(), firstOfAtom_.end() - 1);
    for (std::size_t k = 0; k < list_.size(); ++k)
    {
        const ListedBond& bond = list_[k];
        if (atomOf_[bond.a] < nlocal)
        {
            atomBonds[next[bond.a]++] = 2 * static_cast<int>(k);
        }
        if (atomOf_[bond.b] < nlocal)
        {
            atomBonds[next[bond.b]++] = 2 * static_cast<int>(k) + 1;
        }
    }
    auto partnerTag = [&](int end)
    {
        const BondState& s = list_[end / 2].state;
        return end % 2 ? s.tagA : s.tagB;
    };
    for (int e = 0; e < entries; ++e)
    {
        std::sort(atomBonds.begin() + firstOfAtom_[e], atomBonds.begin() + firstOfAtom_[e + 1],
            [&](int x, int y) { return partnerTag(x) < partnerTag(y); });
    }
    const int unsummed = firstOfAtom_[entries];   // the slot of ghosts' and padding's ends
    slots_.resize(unsummed + 1);
    std::vector<int> slotOfA(batches_.batches() * bondKernelLanes, unsummed), slotOfB = slotOfA;
    for (int n = 0; n < unsummed; ++n)
    {
        const int end = atomBonds[n];
        (end % 2 ? slotOfB : slotOfA)[end / 2] = n;
    }
    for (std::size_t k = 0; k < slotOfA.size(); ++k)
    {
        batches_.setLoadSlots(k, slotOfA[k], slotOfB[k]);
    }
    lastA_.resize(entries);
    for (int e = 0, last = 0; e < entries; ++e)
    {
        last = std::max(last, e);
        for (int n = firstOfAtom_[e]; n < firstOfAtom_[e + 1]; ++n)
        {
            last = std::max(last, list_[atomBonds[n] / 2].a);
        }
        lastA_[e] = last;
    }
    listIsCurrent_ = true;
    listedLocal_ = nlocal;
    listedGhost_ = atom.nghost;
}

BondState IceBondForces::listedState(std::size_t bond) const
{
    BondState state = list_[bond].state;
    batches_.copyHistory(bond, state);
    return state;
}


void IceBondForces::removeFromTable(int atom, long partnerTag)
{
    const int slot = table_.find(atom, partnerTag);
    if (slot >= 0)
    {
        table_.remove(atom, slot);
    }
}


template<class Keep>
std::vector<BondState> IceBondForces::tableBondStatesOf(Keep keep) const
{
    const LAMMPS_NS::Atom& atom = *lmp_.engine().atom;
    std::vector<BondState> states;
    for (int i = 0; i < atom.nlocal; ++i)
    {
        const int n = table_.count(i);
        for (int slot = 0; slot < n; ++slot)
        {
            if (keep(atom.tag[i], table_.partner(i, slot)))
            {
                states.push_back(table_.read(i, slot, atom.tag[i]));
            }
        }
    }
    return states;
}


std::vector<BondState> IceBondForces::tableBondStates() const
{
    return tableBondStatesOf([](long tag, long partner) { return tag < partner; });
}


std::vector<BondState> IceBondForces::bondStatesOfLocalAtoms()
{
    syncTable();
    LAMMPS_NS::Atom& atom = *lmp_.engine().atom;   // map() is not const
    return tableBondStatesOf([&atom](long tag, long partner)
    {
        const int partnerAtom = atom.map(static_cast<int>(partner));
        const bool partnerIsLocal = partnerAtom >= 0 && partnerAtom < atom.nlocal;
        return tag < partner || !partnerIsLocal;
    });
}


std::vector<BondState> IceBondForces::localBondStates() const
{
    if (!listIsCurrent_)
    {
        return tableBondStates();
    }
    const int nlocal = lmp_.engine().atom->nlocal;
    std::vector<BondState> states;
    for (std::size_t k = 0; k < list_.size(); ++k)
    {
        if (intact_[k] && atomOf_[list_[k].a] < nlocal)
        {
            states.push_back(listedState(k));
        }
    }
    std::sort(states.begin(), states.end(), [](const BondState& x, const BondState& y)
    {
        return std::tie(x.tagA, x.tagB) < std::tie(y.tagA, y.tagB);
    });
    return states;
}


void IceBondForces::changeProperties(const IceProperties& props)
{
    if (props.maxBondsPerParticle != ice_.maxBondsPerParticle)
    {
        throw std::logic_error("IceBondForces::changeProperties: the bond capacity per particle cannot change");
    }
    syncTable();    // the list is rebuilt with the new stiffnesses
    models_ = modelsOf(props);
    ice_ = props;
}


void IceBondForces::suspendBreakage(bool suspended)
{
    for (int f = 0; f < nBondFamilies; ++f)
    {
        models_[f].setUnbreakable(suspended || ice_.family(static_cast<BondFamily>(f)).unbreakable);
    }
}


std::unique_ptr<IceBondForces> IceBondForces::define
(
    LiggghtsInstance& lmp,
    const IceProperties& ice,
    const std::string& fixExternalId
)
{
    auto bonds = std::make_unique<IceBondForces>(lmp, ice);
    lmp.command("fix " + fixExternalId + " all external pf/callback 1 1");
    bonds->attach(fixExternalId);
    return bonds;
}


void IceBondForces::attach(const std::string& fixExternalId)
{
    auto& fix = static_cast<LAMMPS_NS::FixExternal&>(lmp_.fix(fixExternalId));
    fix.set_callback(&IceBondForces::callback, this);

    // LIGGGHTS makes fixes only of its own styles: make a placeholder, then
    // put the hooks in its place before the next run's set-up reads which
    // fixes want which calls.
    LAMMPS_NS::LAMMPS& engine = lmp_.engine();
    LAMMPS_NS::Modify& modify = *engine.modify;
    hooksTarget_ = std::make_shared<IceBondForces*>(this);
    std::string id = std::string(BondTable::fixId) + "Hooks";
    if (const int existing = modify.find_fix(id.c_str()); existing >= 0)
    {
        hooks_ = static_cast<IceBondHooks*>(modify.fix[existing]);
        hooks_->retarget(hooksTarget_);
        return;
    }
    lmp_.command("fix " + id + " all external pf/callback 1 1");
    const int index = modify.find_fix(id.c_str());
    std::string group = "all";
    std::string style = "iceBondHooks";
    char* args[] = {id.data(), group.data(), style.data()};
    hooks_ = new IceBondHooks(&engine, args, hooksTarget_);
    delete modify.fix[index];
    modify.fix[index] = hooks_;
    modify.fmask[index] = hooks_->setmask();
}


void IceBondForces::removeBondedPairsFromContacts()
{
    contactListIsStale_ = false;
    const LAMMPS_NS::LAMMPS& engine = lmp_.engine();
    auto* pair = dynamic_cast<LAMMPS_NS::PairGran*>(engine.force->pair);
    if (!pair || !pair->list)
    {
        return;
    }
    LAMMPS_NS::NeighList& list = *pair->list;
    const LAMMPS_NS::NeighList* history = pair->listgranhistory;
    const int values = history ? pair->dnum() : 0;   // as the pair style strides its histories
    const int* tag = engine.atom->tag;
    for (int n = 0; n < list.inum; ++n)
    {
        const int i = list.ilist[n];
        if (table_.count(i) == 0)
        {
            continue;
        }
        // The contact list and its history list are parallel arrays: compact
        // all of them alike.
        int* neighbours = list.firstneigh[i];
        int* touching = history ? history->firstneigh[i] : nullptr;
        double* contactHistory = history ? history->firstdouble[i] : nullptr;
        int kept = 0;
        for (int k = 0; k < list.numneigh[i]; ++k)
        {
            if (table_.find(i, tag[neighbours[k] & NEIGHMASK]) >= 0)
            {
                continue;
            }
            if (kept != k)
            {
                neighbours[kept] = neighbours[k];
                if (history)
                {
                    touching[kept] = touching[k];
                    std::copy_n(contactHistory + values*k, values, contactHistory + values*kept);
                }
            }
            ++kept;
        }
        list.numneigh[i] = kept;
    }
}


void IceBondForces::rebuildContactsOfBrokenBonds()
{
    int broke = brokeThisStep_ ? 1 : 0;
    brokeThisStep_ = false;
    MPI_Allreduce(MPI_IN_PLACE, &broke, 1, MPI_INT, MPI_MAX, lmp_.communicator());
    if (broke && hooks_)
    {
        hooks_->rebuildNeighboursAtNextStep();
    }
}


void IceBondForces::callback(void* self, int64_t, int nlocal, int*, double**, double** fexternal)
{
    // We write forces and torques straight into LIGGGHTS' arrays; the fix's
    // own force array must add nothing.
    for (int i = 0; i < nlocal; ++i)
    {
        fexternal[i][0] = fexternal[i][1] = fexternal[i][2] = 0.0;
    }
    auto& bonds = *static_cast<IceBondForces*>(self);
    bonds.compute();
    bonds.rebuildContactsOfBrokenBonds();
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
    if (listIsCurrent_ && (atom.nlocal != listedLocal_ || atom.nghost != listedGhost_))
    {
        fail("LIGGGHTS moved atoms without synchronising the bond table first (internal error)");
        return;
    }
    if (!listIsCurrent_)
    {
        rebuildList();
    }

    // One pass in spatial order: copy atoms in just ahead of the bonds that
    // need them, and sum each atom's loads soon after its last bond is
    // stepped, while both are still in cache.
    const int entries = static_cast<int>(atomOf_.size());
    int gathered = 0, summed = 0;
    auto gatherUpTo = [&](int last)
    {
        for (; gathered <= last; ++gathered)
        {
            gather(gathered);
        }
    };
    auto sumBelow = [&](int firstUnstepped)
    {
        for (; summed < entries && lastA_[summed] < firstUnstepped; ++summed)
        {
            gatherUpTo(summed);
            sumLoads(summed);
        }
    };
    constexpr int sumEvery = 64;   // entries of a between sums
    constexpr std::size_t prefetchAhead = 2;   // batches
    int steppedBelow = 0;          // every bond with a below this is stepped
    const std::size_t batches = batches_.batches();
    const BondKernelSettings settings = kernelSettings();
    BondKernelResult result;
    for (std::size_t j = 0; j < batches; ++j)
    {
        BondBatch& batch = batches_.batch(j);
        if (batch.a[0] >= steppedBelow + sumEvery)
        {
            steppedBelow = batch.a[0];
            sumBelow(steppedBelow);
        }
        // Broken bonds are stepped too (it is cheaper than leaving them out),
        // and their results dropped; so is the padding.
        int lastAtom = 0;
        for (int l = 0; l < bondKernelLanes; ++l)
        {
            lastAtom = std::max({lastAtom, batch.a[l], batch.b[l]});
        }
        gatherUpTo(lastAtom);
        if (j + prefetchAhead < batches)
        {
            prefetchBEnds(batches_.batch(j + prefetchAhead));
        }
        const int mayBreak = kernel_(particles_.data(), batch, slots_.data(), settings, result);
        const std::size_t first = j * bondKernelLanes;
        for (std::size_t k = first; mayBreak && k < std::min(first + bondKernelLanes, list_.size()); ++k)
        {
            const int lane = static_cast<int>(k - first);
            if ((mayBreak >> lane & 1) && intact_[k])
            {
                breakIfOverLimit(k, result, lane);
            }
        }
    }
    sumBelow(entries);
}


void IceBondForces::prefetchBEnds(const BondBatch& batch) const
{
    // A bond's b atom, and so its slot, can lie far from its a in the atom
    // order: ask for them before the kernel needs them.
    for (int l = 0; l < bondKernelLanes; ++l)
    {
        const char* atom = reinterpret_cast<const char*>(&particles_[batch.b[l]]);
        const char* slot = reinterpret_cast<const char*>(&slots_[batch.loadOfB[l]]);
        __builtin_prefetch(atom);
        __builtin_prefetch(atom + sizeof(KernelAtom) - 1);
        __builtin_prefetch(slot, 1);
        __builtin_prefetch(slot + sizeof(BondEndLoad) - 1, 1);
    }
}


void IceBondForces::gather(int entry)
{
    const LAMMPS_NS::Atom& atom = *lmp_.engine().atom;
    const int i = atomOf_[entry];
    KernelAtom& p = particles_[entry];
    for (int c = 0; c < 3; ++c)
    {
        p.position[c] = atom.x[i][c];
        p.velocity[c] = atom.v[i][c];
        p.angularVelocity[c] = atom.omega[i][c];
    }
}


BondKernelSettings IceBondForces::kernelSettings() const
{
    BondKernelSettings settings;
    settings.dt = lmp_.timeStep();
    settings.viscous = ice_.damping.model == DampingModel::viscous && ice_.damping.dampingRatio > 0.0;
    settings.dampingRatio = ice_.damping.dampingRatio;
    return settings;
}


void IceBondForces::breakIfOverLimit(std::size_t k, const BondKernelResult& result, int l)
{
    const ListedBond& bond = list_[k];
    const BondState& state = bond.state;   // its tags, family and strengths
    const BreakMode broke = models_[static_cast<int>(state.family)].breakMode
    (
        state, stiffnesses_[bond.stiffness], result.springNormalForce[l],
        result.shearForce2[l], result.twistTorque2[l], result.bendingTorque2[l]
    );
    if (broke != BreakMode::none)
    {
        const int nlocal = lmp_.engine().atom->nlocal;
        const int a = atomOf_[bond.a];
        const int b = atomOf_[bond.b];
        if (a < nlocal)
        {
            const Vec3 centre(result.centre[0][l], result.centre[1][l], result.centre[2][l]);
            const double* const* x = lmp_.engine().atom->x;
            const Vec3 separation(x[b][0] - x[a][0], x[b][1] - x[a][1], x[b][2] - x[a][2]);
            breaks_.push_back({lmp_.time(), centre, separation, state.tagA, state.tagB, state.family, broke});
            removeFromTable(a, state.tagB);
        }
        if (b < nlocal)
        {
            removeFromTable(b, state.tagA);
        }
        intact_[k] = 0;
        brokeThisStep_ = true;
        // Adding -0 leaves every sum as it is, even a sum of -0. From now on
        // the kernel writes the bond's loads where nobody sums them.
        const BondEndLoad none{{-0.0, -0.0, -0.0}, {-0.0, -0.0, -0.0}};
        slots_[batches_.loadOfA(k)] = none;
        slots_[batches_.loadOfB(k)] = none;
        const int unsummed = static_cast<int>(slots_.size()) - 1;
        batches_.setLoadSlots(k, unsummed, unsummed);
    }
}


Vec3 IceBondForces::localForceAcross(long firstTag) const
{
    // The list, its load slots and atomOf_ stay as the last step left them
    // until the next step rebuilds them, even after the table took over.
    Vec3 sum = Vec3::Zero();
    for (std::size_t k = 0; k < list_.size(); ++k)
    {
        const ListedBond& bond = list_[k];
        const bool aAbove = bond.state.tagA >= firstTag;
        if (!intact_[k] || aAbove == (bond.state.tagB >= firstTag))
        {
            continue;
        }
        if (atomOf_[aAbove ? bond.a : bond.b] >= listedLocal_)
        {
            continue;   // a ghost: its owner counts it
        }
        const BondEndLoad& load = slots_[aAbove ? batches_.loadOfA(k) : batches_.loadOfB(k)];
        sum += Vec3(load.force[0], load.force[1], load.force[2]);
    }
    return sum;
}


void IceBondForces::sumLoads(int entry)
{
    LAMMPS_NS::Atom& atom = *lmp_.engine().atom;
    const int i = atomOf_[entry];
    if (i >= atom.nlocal)
    {
        return;   // a ghost: its owner sums its loads
    }
    Vec3 force = row(atom.f, i);
    Vec3 moment = row(atom.torque, i);
    for (int n = firstOfAtom_[entry]; n < firstOfAtom_[entry + 1]; ++n)
    {
        const BondEndLoad& slot = slots_[n];
        for (int c = 0; c < 3; ++c)
        {
            force[c] += slot.force[c];
            moment[c] += slot.moment[c];
        }
    }

    if (!std::isfinite(force.squaredNorm()) || !std::isfinite(moment.squaredNorm()))
    {
        std::ostringstream msg;
        msg << "non-finite force on particle " << atom.tag[i] << " at (" << row(atom.x, i).transpose()
            << "): the run has blown up";
        fail(msg.str());
    }
    else if (ice_.damping.model == DampingModel::hysteretic && ice_.damping.alpha > 0.0)
    {
        const KernelAtom& p = particles_[entry];
        applyHystereticDamping(force, Vec3(p.velocity[0], p.velocity[1], p.velocity[2]), ice_.damping.alpha);
        applyHystereticDamping
        (
            moment, Vec3(p.angularVelocity[0], p.angularVelocity[1], p.angularVelocity[2]), ice_.damping.alpha
        );
    }
    for (int c = 0; c < 3; ++c)
    {
        atom.f[i][c] = force[c];
        atom.torque[i][c] = moment[c];
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
    if (listIsCurrent_)
    {
        for (std::size_t k = 0; k < list_.size(); ++k)
        {
            const ListedBond& bond = list_[k];
            const int a = atomOf_[bond.a];
            if (intact_[k] && a < atom.nlocal)
            {
                energy += models_[static_cast<int>(bond.state.family)]
                    .potentialEnergy(listedState(k), particle(a), particle(atomOf_[bond.b]));
            }
        }
        return energy;
    }
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
