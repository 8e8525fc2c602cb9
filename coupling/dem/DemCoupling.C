#include "DemCoupling.H"

#include "FpeTrapsOff.H"
#include "LiggghtsInstance.H"

#include "lammps.h"
#include "atom.h"
#include "domain.h"
#include "fix_external.h"
#include "comm.h"
#include "error.h"

#include <mpi.h>

#include <algorithm>
#include <numeric>

namespace iceCoupling
{

namespace
{

constexpr int fieldsPerParticle = 9;   // tag, x[3], v[3], diameter, mass

//- What one rank sends: the values for rank 0, then for rank 1, ..., and how
//  many values go to each.
struct RankOrderedValues
{
    std::vector<double> values;
    std::vector<int> counts;
};


RankOrderedValues inRankOrder(const std::vector<std::vector<double>>& toRank)
{
    RankOrderedValues out;
    for (const std::vector<double>& part : toRank)
    {
        out.values.insert(out.values.end(), part.begin(), part.end());
        out.counts.push_back(static_cast<int>(part.size()));
    }
    return out;
}


//- Sends each rank its part of `sent`; returns what arrived, by sending rank,
//  and how many values came from each.
std::vector<double> allToAll(const RankOrderedValues& sent, MPI_Comm comm, std::vector<int>& receiveCounts)
{
    const int ranks = static_cast<int>(sent.counts.size());
    std::vector<int> sendOffsets(ranks, 0), receiveOffsets(ranks, 0);
    for (int r = 1; r < ranks; ++r)
    {
        sendOffsets[r] = sendOffsets[r - 1] + sent.counts[r - 1];
    }
    receiveCounts.assign(ranks, 0);
    MPI_Alltoall(sent.counts.data(), 1, MPI_INT, receiveCounts.data(), 1, MPI_INT, comm);
    for (int r = 1; r < ranks; ++r)
    {
        receiveOffsets[r] = receiveOffsets[r - 1] + receiveCounts[r - 1];
    }
    std::vector<double> received(receiveOffsets.back() + receiveCounts.back());
    MPI_Alltoallv(sent.values.data(), sent.counts.data(), sendOffsets.data(), MPI_DOUBLE,
                  received.data(), receiveCounts.data(), receiveOffsets.data(), MPI_DOUBLE, comm);
    return received;
}

} // namespace


DemCoupling::DemCoupling(iceDEM::LiggghtsInstance& lmp, const std::string& fixExternalId)
:
    lmp_(lmp)
{
    auto& fix = static_cast<LAMMPS_NS::FixExternal&>(lmp_.fix(fixExternalId));
    fix.set_callback(&DemCoupling::callback, this);
}


std::vector<double> DemCoupling::localRows() const
{
    const LAMMPS_NS::Atom& atom = *lmp_.engine().atom;
    const int nlocal = atom.nlocal;
    std::vector<double> rows;
    rows.reserve(fieldsPerParticle*nlocal);
    for (int i = 0; i < nlocal; ++i)
    {
        rows.push_back(atom.tag[i]);
        // LIGGGHTS wraps atoms across periodic boundaries only when it
        // re-neighbours; the fluid mesh needs the position inside the box.
        double x[3] = {atom.x[i][0], atom.x[i][1], atom.x[i][2]};
        lmp_.engine().domain->remap(x);
        rows.insert(rows.end(), x, x + 3);
        rows.insert(rows.end(), atom.v[i], atom.v[i] + 3);
        rows.push_back(2.0*atom.radius[i]);
        rows.push_back(atom.rmass[i]);
    }
    return rows;
}


std::vector<CouplingParticle> DemCoupling::exchangeRows
(
    const std::vector<double>& rows, const std::vector<std::vector<int>>& rowsForRank
) const
{
    const int ranks = static_cast<int>(rowsForRank.size());
    RankOrderedValues sent;
    for (int r = 0; r < ranks; ++r)
    {
        for (const int row : rowsForRank[r])
        {
            sent.values.insert(sent.values.end(), &rows[fieldsPerParticle*row], &rows[fieldsPerParticle*(row + 1)]);
        }
        sent.counts.push_back(static_cast<int>(fieldsPerParticle*rowsForRank[r].size()));
    }
    std::vector<int> receiveCounts;
    const std::vector<double> received(allToAll(sent, lmp_.communicator(), receiveCounts));

    std::vector<CouplingParticle> particles;
    particles.reserve(received.size()/fieldsPerParticle);
    std::size_t k = 0;
    for (int r = 0; r < ranks; ++r)
    {
        for (const std::size_t end = k + receiveCounts[r]; k < end; k += fieldsPerParticle)
        {
            const double* row = &received[k];
            particles.push_back({static_cast<long>(row[0]), {row[1], row[2], row[3]},
                                 {row[4], row[5], row[6]}, row[7], row[8], r});
        }
    }
    std::sort(particles.begin(), particles.end(),
              [](const CouplingParticle& a, const CouplingParticle& b) { return a.tag < b.tag; });
    return particles;
}


std::vector<CouplingParticle> DemCoupling::gatherAll() const
{
    int ranks = 1;
    MPI_Comm_size(lmp_.communicator(), &ranks);
    const std::vector<double> rows(localRows());
    std::vector<int> everyRow(rows.size()/fieldsPerParticle);
    std::iota(everyRow.begin(), everyRow.end(), 0);
    return exchangeRows(rows, std::vector<std::vector<int>>(ranks, everyRow));
}


std::vector<CouplingParticle> DemCoupling::gatherNear(const CouplingRegion& region) const
{
    MPI_Comm comm = lmp_.communicator();
    int ranks = 1;
    MPI_Comm_size(comm, &ranks);
    std::vector<double> regions(6*ranks);
    const double mine[6] =
        {region.lower[0], region.lower[1], region.lower[2], region.upper[0], region.upper[1], region.upper[2]};
    MPI_Allgather(mine, 6, MPI_DOUBLE, regions.data(), 6, MPI_DOUBLE, comm);

    const std::vector<double> rows(localRows());
    std::vector<std::vector<int>> rowsForRank(ranks);
    for (int i = 0; i < static_cast<int>(rows.size()/fieldsPerParticle); ++i)
    {
        const double* row = &rows[fieldsPerParticle*i];
        const double radius = 0.5*row[7];
        bool anywhere = false;
        for (int r = 0; r < ranks; ++r)
        {
            // Distance from the centre to the box, against the radius.
            double distance2 = 0;
            for (int k = 0; k < 3; ++k)
            {
                const double below = regions[6*r + k] - row[1 + k];
                const double above = row[1 + k] - regions[6*r + 3 + k];
                const double outside = std::max({below, above, 0.0});
                distance2 += outside*outside;
            }
            if (distance2 <= radius*radius)
            {
                rowsForRank[r].push_back(i);
                anywhere = true;
            }
        }
        if (!anywhere)
        {
            rowsForRank[0].push_back(i);
        }
    }
    return exchangeRows(rows, rowsForRank);
}


long DemCoupling::particleCount() const
{
    return static_cast<long>(lmp_.engine().atom->natoms);
}


std::vector<int> DemCoupling::ranksNear(const std::array<double, 3>& position, double margin) const
{
    const LAMMPS_NS::Domain& domain = *lmp_.engine().domain;
    std::vector<int> near;
    const int ranks = static_cast<int>(ghostBoxes_.size()/6);
    for (int r = 0; r < ranks; ++r)
    {
        const double* box = &ghostBoxes_[6*r];
        bool inside = true;
        for (int k = 0; k < 3 && inside; ++k)
        {
            bool inAnImage = false;
            for (const int image : {0, -1, 1})
            {
                if (image != 0 && !domain.periodicity[k])
                {
                    continue;
                }
                const double x = position[k] + image*domain.prd[k];
                inAnImage = inAnImage || (x >= box[k] - margin && x <= box[3 + k] + margin);
            }
            inside = inAnImage;
        }
        if (inside)
        {
            near.push_back(r);
        }
    }
    return near;
}


void DemCoupling::setForces
(
    const std::vector<CouplingParticle>& particles,
    const std::vector<std::array<double, 3>>& forces
)
{
    const LAMMPS_NS::LAMMPS& engine = lmp_.engine();
    MPI_Comm comm = lmp_.communicator();
    int ranks = 1;
    MPI_Comm_size(comm, &ranks);

    // Each rank's sub-box, widened by the ghost cut-off (zero before
    // LIGGGHTS' first set-up) and each particle's diameter: an atom that
    // reaches a rank before the next exchange is within it now.
    double mine[6];
    for (int k = 0; k < 3; ++k)
    {
        mine[k] = engine.domain->sublo[k] - engine.comm->cutghost[k];
        mine[3 + k] = engine.domain->subhi[k] + engine.comm->cutghost[k];
    }
    ghostBoxes_.resize(6*ranks);
    MPI_Allgather(mine, 6, MPI_DOUBLE, ghostBoxes_.data(), 6, MPI_DOUBLE, comm);

    constexpr int width = 4;   // tag, force
    std::vector<std::vector<double>> toRank(ranks);
    for (std::size_t p = 0; p < particles.size(); ++p)
    {
        const double row[width] = {static_cast<double>(particles[p].tag), forces[p][0], forces[p][1], forces[p][2]};
        for (const int r : ranksNear(particles[p].position, particles[p].diameter))
        {
            toRank[r].insert(toRank[r].end(), row, row + width);
        }
    }
    std::vector<int> receiveCounts;
    const std::vector<double> received(allToAll(inRankOrder(toRank), comm, receiveCounts));

    // The shares of the ranks holding each particle, summed in the order of those ranks.
    std::unordered_map<long, std::array<double, 3>> previous(std::move(forceOfTag_));
    forceOfTag_.clear();
    for (std::size_t k = 0; k < received.size(); k += width)
    {
        auto& force = forceOfTag_.emplace(static_cast<long>(received[k]), std::array<double, 3>{0.0, 0.0, 0.0}).first->second;
        for (int c = 0; c < 3; ++c)
        {
            force[c] += received[k + 1 + c];
        }
    }

    // Velocity Verlet starts the next step with a half kick from the force
    // array of the last one, which holds the old fluid force: swap it for the
    // new one, or each coupling interval would get half a DEM step of the
    // previous interval's force (momentum the fluid never gave).
    if (started_)
    {
        LAMMPS_NS::Atom& atom = *engine.atom;
        for (int i = 0; i < atom.nlocal; ++i)
        {
            const auto old = previous.find(atom.tag[i]);
            const auto now = forceOfTag_.find(atom.tag[i]);
            for (int k = 0; k < 3; ++k)
            {
                atom.f[i][k] += (now != forceOfTag_.end() ? now->second[k] : 0.0)
                              - (old != previous.end() ? old->second[k] : 0.0);
            }
        }
    }
    forcesSet_ = true;
    orderedTags_.clear();   // the next step looks the new forces up
}


void DemCoupling::advance(long steps)
{
    // The first run sets LIGGGHTS up (neighbour lists, fixes); later ones continue it.
    const FpeTrapsOff untrapped;
    lmp_.command("run " + std::to_string(steps) + (started_ ? " pre no post no" : " post no"));
    started_ = true;
}


void DemCoupling::callback(void* self, int64_t, int nlocal, int* tags, double**, double** fexternal)
{
    static_cast<DemCoupling*>(self)->apply(nlocal, tags, fexternal);
}


void DemCoupling::apply(int nlocal, const int* tags, double** fexternal)
{
    const bool sameOrder =
        orderedTags_.size() == static_cast<std::size_t>(nlocal)
     && std::equal(tags, tags + nlocal, orderedTags_.begin());
    if (!sameOrder)
    {
        orderedTags_.assign(tags, tags + nlocal);
        orderedForces_.resize(nlocal);
        for (int i = 0; i < nlocal; ++i)
        {
            const auto force = forceOfTag_.find(tags[i]);
            if (force != forceOfTag_.end())
            {
                orderedForces_[i] = force->second;
            }
            else if (!forcesSet_)
            {
                // No force yet (LIGGGHTS' set-up runs before the first exchange): none.
                orderedForces_[i] = {0.0, 0.0, 0.0};
            }
            else
            {
                lmp_.engine().error->one(FLERR, ("the fluid force of atom " + std::to_string(tags[i])
                    + " is not on this rank: it came from further than the ghost cut-off within one"
                    " coupling interval; lower couplingInterval (constant/couplingProperties)").c_str());
            }
        }
    }
    for (int i = 0; i < nlocal; ++i)
    {
        for (int k = 0; k < 3; ++k)
        {
            fexternal[i][k] = orderedForces_[i][k];
        }
    }
}

} // namespace iceCoupling
