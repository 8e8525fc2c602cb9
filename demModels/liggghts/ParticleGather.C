#include "ParticleGather.H"

#include "Checkpoint.H"
#include "InputError.H"
#include "LiggghtsInstance.H"

#include "atom.h"
#include "lammps.h"

#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace iceDEM
{

std::vector<double> gatherDoubles(MPI_Comm comm, const std::vector<double>& local)
{
    int rank = 0, size = 1;
    MPI_Comm_rank(comm, &rank);
    MPI_Comm_size(comm, &size);
    int count = static_cast<int>(local.size());
    std::vector<int> counts(size), offsets(size, 0);
    MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm);
    std::vector<double> all;
    if (rank == 0)
    {
        std::partial_sum(counts.begin(), counts.end() - 1, offsets.begin() + 1);
        all.resize(std::accumulate(counts.begin(), counts.end(), std::size_t(0)));
    }
    MPI_Gatherv
    (
        local.data(), count, MPI_DOUBLE,
        all.data(), counts.data(), offsets.data(), MPI_DOUBLE, 0, comm
    );
    return all;
}


double netForceOnTagsFrom(const LiggghtsInstance& lmp, MPI_Comm comm, long firstTag, int axis)
{
    const LAMMPS_NS::Atom& atom = *lmp.engine().atom;
    double local = 0.0;
    for (int i = 0; i < atom.nlocal; ++i)
    {
        if (atom.tag[i] >= firstTag) local += atom.f[i][axis];
    }
    return sumOverRanks(comm, local);
}


double totalKineticEnergy(const LiggghtsInstance& lmp)
{
    const LAMMPS_NS::Atom& atom = *lmp.engine().atom;
    double e = 0.0;
    for (int i = 0; i < atom.nlocal; ++i)
    {
        const double m = atom.rmass[i];
        const double inertia = 0.4 * m * atom.radius[i] * atom.radius[i];
        for (int k = 0; k < 3; ++k)
        {
            e += 0.5 * m * atom.v[i][k] * atom.v[i][k] + 0.5 * inertia * atom.omega[i][k] * atom.omega[i][k];
        }
    }
    return sumOverRanks(lmp.communicator(), e);
}


FastestParticle fastestParticle(const LiggghtsInstance& lmp)
{
    const LAMMPS_NS::Atom& atom = *lmp.engine().atom;
    int fastest = -1;
    double speed2 = -1.0;
    for (int i = 0; i < atom.nlocal; ++i)
    {
        const double v2 = atom.v[i][0] * atom.v[i][0] + atom.v[i][1] * atom.v[i][1] + atom.v[i][2] * atom.v[i][2];
        if (v2 > speed2)
        {
            speed2 = v2;
            fastest = i;
        }
    }
    struct { double value; int rank; } local{speed2, 0}, global{};
    MPI_Comm_rank(lmp.communicator(), &local.rank);
    MPI_Allreduce(&local, &global, 1, MPI_DOUBLE_INT, MPI_MAXLOC, lmp.communicator());
    // The owner sends tag and position: 4 numbers.
    double data[4] = {0.0, 0.0, 0.0, 0.0};
    if (local.rank == global.rank && fastest >= 0)
    {
        data[0] = static_cast<double>(atom.tag[fastest]);
        for (int k = 0; k < 3; ++k) data[k + 1] = atom.x[fastest][k];
    }
    MPI_Bcast(data, 4, MPI_DOUBLE, global.rank, lmp.communicator());
    FastestParticle f;
    f.speed = std::sqrt(std::max(global.value, 0.0));
    f.tag = static_cast<long>(data[0]);
    f.position = Vec3(data[1], data[2], data[3]);
    return f;
}


std::vector<BondState> gatherBondStates(MPI_Comm comm, const IceBondForces& bonds)
{
    std::vector<double> flat;
    for (const BondState& b : bonds.localBondStates())
    {
        appendBondState(flat, b);
    }
    const std::vector<double> all = gatherDoubles(comm, flat);
    std::vector<BondState> states;
    for (std::size_t k = 0; k + bondStateDoubles <= all.size(); k += bondStateDoubles)
    {
        states.push_back(bondStateFrom(&all[k]));
    }
    return states;
}


std::vector<Vec3> allPositionsByTag(const LiggghtsInstance& lmp)
{
    const LAMMPS_NS::Atom& atom = *lmp.engine().atom;
    MPI_Comm comm = lmp.communicator();
    int size = 1;
    MPI_Comm_size(comm, &size);
    std::vector<double> local;
    local.reserve(4*atom.nlocal);
    for (int i = 0; i < atom.nlocal; ++i)
    {
        local.push_back(atom.tag[i]);
        local.insert(local.end(), atom.x[i], atom.x[i] + 3);
    }
    int count = static_cast<int>(local.size());
    std::vector<int> counts(size), offsets(size, 0);
    MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, comm);
    std::partial_sum(counts.begin(), counts.end() - 1, offsets.begin() + 1);
    std::vector<double> all(std::accumulate(counts.begin(), counts.end(), std::size_t(0)));
    MPI_Allgatherv
    (
        local.data(), count, MPI_DOUBLE,
        all.data(), counts.data(), offsets.data(), MPI_DOUBLE, comm
    );
    // Tags run from 1 to the number of particles made: a larger tag than
    // particles present means some left the box (LIGGGHTS drops them).
    long maxTag = 0;
    for (std::size_t k = 0; k + 3 < all.size(); k += 4)
    {
        maxTag = std::max(maxTag, static_cast<long>(all[k]));
    }
    const long present = static_cast<long>(all.size()/4);
    if (maxTag > present || static_cast<long>(atom.natoms) > present)
    {
        throw RunError(std::to_string(std::max(maxTag, static_cast<long>(atom.natoms)) - present)
            + " particle(s) left the simulation box by step " + std::to_string(lmp.step())
            + " (" + std::to_string(present) + " of the tags 1-" + std::to_string(maxTag)
            + " remain): the run has blown up");
    }
    std::vector<Vec3> positions(present, Vec3::Constant(std::nan("")));
    for (std::size_t k = 0; k + 3 < all.size(); k += 4)
    {
        const long tag = static_cast<long>(all[k]);
        positions[tag - 1] = Vec3(all[k + 1], all[k + 2], all[k + 3]);
    }
    return positions;
}


GatheredState gatherState(const LiggghtsInstance& lmp, const IceBondForces& bonds, int fixedType)
{
    const LAMMPS_NS::Atom& atom = *lmp.engine().atom;
    constexpr int perAtom = 13;
    std::vector<double> local;
    local.reserve(atom.nlocal * perAtom);
    for (int i = 0; i < atom.nlocal; ++i)
    {
        local.push_back(atom.tag[i]);
        for (double** a : {atom.x, atom.v, atom.f})
        {
            local.insert(local.end(), a[i], a[i] + 3);
        }
        local.push_back(atom.radius[i]);
        local.push_back(bonds.bondCount(i));
        local.push_back(atom.type[i] == fixedType ? 1.0 : 0.0);
    }
    std::vector<double> linkData;
    for (const BondLink& l : bonds.localLinks())
    {
        linkData.insert(linkData.end(), {double(l.tagA), double(l.tagB), double(l.family)});
    }

    GatheredState state;
    const std::vector<double> all = gatherDoubles(lmp.communicator(), local);
    const std::vector<double> allLinks = gatherDoubles(lmp.communicator(), linkData);

    const std::size_t n = all.size() / perAtom;
    std::vector<std::size_t> order(n);
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b)
    {
        return all[a * perAtom] < all[b * perAtom];
    });
    ParticleFrame& p = state.particles;
    for (std::size_t k : order)
    {
        const double* r = &all[k * perAtom];
        const long tag = static_cast<long>(r[0]);
        state.indexOfTag[tag] = p.tag.size();
        p.tag.push_back(tag);
        p.position.emplace_back(r[1], r[2], r[3]);
        p.velocity.emplace_back(r[4], r[5], r[6]);
        p.force.emplace_back(r[7], r[8], r[9]);
        p.radius.push_back(r[10]);
        p.bondCount.push_back(static_cast<int>(r[11]));
        p.fixed.push_back(static_cast<int>(r[12]));
    }
    for (std::size_t k = 0; k + 2 < allLinks.size(); k += 3)
    {
        state.links.push_back
        ({
            static_cast<long>(allLinks[k]),
            static_cast<long>(allLinks[k + 1]),
            static_cast<int>(allLinks[k + 2])
        });
    }
    return state;
}


std::vector<BreakEvent> gatherBreakEvents(MPI_Comm comm, const std::vector<BreakEvent>& local)
{
    constexpr int perEvent = 11;
    std::vector<double> data;
    for (const BreakEvent& e : local)
    {
        data.insert
        (
            data.end(),
            {
                e.time, e.position.x(), e.position.y(), e.position.z(),
                e.separation.x(), e.separation.y(), e.separation.z(),
                double(e.tagA), double(e.tagB),
                double(static_cast<int>(e.family)), double(static_cast<int>(e.mode))
            }
        );
    }
    const std::vector<double> all = gatherDoubles(comm, data);
    std::vector<BreakEvent> events;
    for (std::size_t k = 0; k + perEvent - 1 < all.size(); k += perEvent)
    {
        BreakEvent e;
        e.time = all[k];
        e.position = Vec3(all[k + 1], all[k + 2], all[k + 3]);
        e.separation = Vec3(all[k + 4], all[k + 5], all[k + 6]);
        e.tagA = static_cast<long>(all[k + 7]);
        e.tagB = static_cast<long>(all[k + 8]);
        e.family = static_cast<BondFamily>(static_cast<int>(all[k + 9]));
        e.mode = static_cast<BreakMode>(static_cast<int>(all[k + 10]));
        events.push_back(e);
    }
    return events;
}


double sumOverRanks(MPI_Comm comm, double local)
{
    double total = 0.0;
    MPI_Allreduce(&local, &total, 1, MPI_DOUBLE, MPI_SUM, comm);
    return total;
}


long sumOverRanks(MPI_Comm comm, long local)
{
    long total = 0;
    MPI_Allreduce(&local, &total, 1, MPI_LONG, MPI_SUM, comm);
    return total;
}

} // namespace iceDEM
