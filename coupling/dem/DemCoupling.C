#include "DemCoupling.H"

#include "FpeTrapsOff.H"
#include "LiggghtsInstance.H"

#include "lammps.h"
#include "atom.h"
#include "domain.h"
#include "fix_external.h"

#include <mpi.h>

#include <algorithm>

namespace iceCoupling
{

namespace
{

constexpr int fieldsPerParticle = 9;   // tag, x[3], v[3], diameter, mass

} // namespace


DemCoupling::DemCoupling(iceDEM::LiggghtsInstance& lmp, const std::string& fixExternalId)
:
    lmp_(lmp)
{
    auto& fix = static_cast<LAMMPS_NS::FixExternal&>(lmp_.fix(fixExternalId));
    fix.set_callback(&DemCoupling::callback, this);
}


std::vector<CouplingParticle> DemCoupling::gatherAll() const
{
    const LAMMPS_NS::Atom& atom = *lmp_.engine().atom;
    const int nlocal = atom.nlocal;
    std::vector<double> local;
    local.reserve(fieldsPerParticle*nlocal);
    for (int i = 0; i < nlocal; ++i)
    {
        local.push_back(atom.tag[i]);
        // LIGGGHTS wraps atoms across periodic boundaries only when it
        // re-neighbours; the fluid mesh needs the position inside the box.
        double x[3] = {atom.x[i][0], atom.x[i][1], atom.x[i][2]};
        lmp_.engine().domain->remap(x);
        local.insert(local.end(), x, x + 3);
        local.insert(local.end(), atom.v[i], atom.v[i] + 3);
        local.push_back(2.0*atom.radius[i]);
        local.push_back(atom.rmass[i]);
    }

    MPI_Comm comm = lmp_.communicator();
    int ranks = 1;
    MPI_Comm_size(comm, &ranks);
    std::vector<int> counts(ranks), offsets(ranks, 0);
    const int localCount = static_cast<int>(local.size());
    MPI_Allgather(&localCount, 1, MPI_INT, counts.data(), 1, MPI_INT, comm);
    for (int r = 1; r < ranks; ++r)
    {
        offsets[r] = offsets[r - 1] + counts[r - 1];
    }
    std::vector<double> all(offsets.back() + counts.back());
    MPI_Allgatherv(local.data(), localCount, MPI_DOUBLE, all.data(), counts.data(),
                   offsets.data(), MPI_DOUBLE, comm);

    std::vector<CouplingParticle> particles(all.size()/fieldsPerParticle);
    for (std::size_t p = 0; p < particles.size(); ++p)
    {
        const double* row = &all[fieldsPerParticle*p];
        particles[p] = {static_cast<long>(row[0]), {row[1], row[2], row[3]},
                        {row[4], row[5], row[6]}, row[7], row[8]};
    }
    std::sort(particles.begin(), particles.end(),
              [](const CouplingParticle& a, const CouplingParticle& b) { return a.tag < b.tag; });
    return particles;
}


void DemCoupling::setForces
(
    const std::vector<CouplingParticle>& particles,
    const std::vector<std::array<double, 3>>& forces
)
{
    long maxTag = 0;
    for (const CouplingParticle& p : particles)
    {
        maxTag = std::max(maxTag, p.tag);
    }
    std::vector<std::array<double, 3>> previous(std::move(forceOfTag_));
    forceOfTag_.assign(maxTag + 1, {0.0, 0.0, 0.0});
    for (std::size_t p = 0; p < particles.size(); ++p)
    {
        forceOfTag_[particles[p].tag] = forces[p];
    }

    // Velocity Verlet starts the next step with a half kick from the force
    // array of the last one, which holds the old fluid force: swap it for the
    // new one, or each coupling interval would get half a DEM step of the
    // previous interval's force (momentum the fluid never gave).
    if (started_)
    {
        LAMMPS_NS::Atom& atom = *lmp_.engine().atom;
        for (int i = 0; i < atom.nlocal; ++i)
        {
            const long tag = atom.tag[i];
            for (int k = 0; k < 3; ++k)
            {
                const double old = tag < static_cast<long>(previous.size()) ? previous[tag][k] : 0.0;
                const double now = tag < static_cast<long>(forceOfTag_.size()) ? forceOfTag_[tag][k] : 0.0;
                atom.f[i][k] += now - old;
            }
        }
    }
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
    static_cast<const DemCoupling*>(self)->apply(nlocal, tags, fexternal);
}


void DemCoupling::apply(int nlocal, const int* tags, double** fexternal) const
{
    for (int i = 0; i < nlocal; ++i)
    {
        const long tag = tags[i];
        const bool known = tag < static_cast<long>(forceOfTag_.size());
        for (int k = 0; k < 3; ++k)
        {
            fexternal[i][k] = known ? forceOfTag_[tag][k] : 0.0;
        }
    }
}

} // namespace iceCoupling
