#include "particleRowExchange.H"
#include "Pstream.H"
#include "error.H"

#include <mpi.h>

#include <algorithm>
#include <numeric>

namespace Foam
{
namespace iceCoupling
{

namespace
{

MPI_Datatype mpiType(const double*) { return MPI_DOUBLE; }
MPI_Datatype mpiType(const int*) { return MPI_INT; }

std::vector<int> offsetsOf(const std::vector<int>& counts)
{
    std::vector<int> offsets(counts.size(), 0);
    std::partial_sum(counts.begin(), counts.end() - 1, offsets.begin() + 1);
    return offsets;
}

std::vector<int> scaled(const std::vector<int>& v, int width)
{
    std::vector<int> out(v);
    for (int& x : out)
    {
        x *= width;
    }
    return out;
}

} // namespace


particleRowExchange::particleRowExchange
(
    const std::vector<::iceCoupling::CouplingParticle>& particles
)
:
    particles_(particles.size()),
    parallel_(Pstream::parRun())
{
    if (!parallel_)
    {
        return;
    }
    const int ranks = Pstream::nProcs();
    sendCounts_.assign(ranks, 0);
    for (const auto& p : particles)
    {
        if (p.rank < 0 || p.rank >= ranks)
        {
            FatalErrorInFunction
                << "particle " << p.tag << " names DEM rank " << p.rank << " of " << ranks
                << abort(FatalError);
        }
        ++sendCounts_[p.rank];
    }
    sendOffsets_ = offsetsOf(sendCounts_);
    sendOrder_.resize(particles.size());
    std::vector<int> next(sendOffsets_);
    for (std::size_t i = 0; i < particles.size(); ++i)
    {
        sendOrder_[next[particles[i].rank]++] = static_cast<int>(i);
    }

    receiveCounts_.assign(ranks, 0);
    MPI_Alltoall(sendCounts_.data(), 1, MPI_INT, receiveCounts_.data(), 1, MPI_INT, MPI_COMM_WORLD);
    receiveOffsets_ = offsetsOf(receiveCounts_);

    std::vector<long> sentTags(particles.size());
    for (std::size_t k = 0; k < sendOrder_.size(); ++k)
    {
        sentTags[k] = particles[sendOrder_[k]].tag;
    }
    std::vector<long> receivedTags(receiveOffsets_.back() + receiveCounts_.back());
    MPI_Alltoallv(sentTags.data(), sendCounts_.data(), sendOffsets_.data(), MPI_LONG,
                  receivedTags.data(), receiveCounts_.data(), receiveOffsets_.data(), MPI_LONG,
                  MPI_COMM_WORLD);

    std::vector<long> distinct(receivedTags);
    std::sort(distinct.begin(), distinct.end());
    distinct.erase(std::unique(distinct.begin(), distinct.end()), distinct.end());
    slots_ = static_cast<int>(distinct.size());
    slotOfReceived_.resize(receivedTags.size());
    for (std::size_t k = 0; k < receivedTags.size(); ++k)
    {
        slotOfReceived_[k] = static_cast<int>
        (
            std::lower_bound(distinct.begin(), distinct.end(), receivedTags[k]) - distinct.begin()
        );
    }
}


template<class Value, class Combine>
void particleRowExchange::combine(std::vector<Value>& rows, int width, Combine combineInto) const
{
    if (rows.size() != particles_*width)
    {
        FatalErrorInFunction
            << rows.size() << " values for " << particles_ << " particles of " << width << " each"
            << abort(FatalError);
    }
    if (!parallel_)
    {
        return;
    }
    std::vector<Value> sent(rows.size());
    for (std::size_t k = 0; k < sendOrder_.size(); ++k)
    {
        std::copy_n(&rows[width*sendOrder_[k]], width, &sent[width*k]);
    }
    const std::vector<int> sendCounts(scaled(sendCounts_, width)), sendOffsets(scaled(sendOffsets_, width));
    const std::vector<int> receiveCounts(scaled(receiveCounts_, width));
    const std::vector<int> receiveOffsets(scaled(receiveOffsets_, width));
    std::vector<Value> received(width*slotOfReceived_.size());
    const MPI_Datatype type = mpiType(rows.data());
    MPI_Alltoallv(sent.data(), sendCounts.data(), sendOffsets.data(), type,
                  received.data(), receiveCounts.data(), receiveOffsets.data(), type, MPI_COMM_WORLD);

    // Combined in the order the rows arrived, by sending rank: the same
    // result every run on the same ranks.
    std::vector<Value> combined(width*slots_);
    std::vector<bool> seen(slots_, false);
    for (std::size_t k = 0; k < slotOfReceived_.size(); ++k)
    {
        const int slot = slotOfReceived_[k];
        Value* target = &combined[width*slot];
        const Value* row = &received[width*k];
        if (seen[slot])
        {
            for (int c = 0; c < width; ++c)
            {
                target[c] = combineInto(target[c], row[c]);
            }
        }
        else
        {
            std::copy_n(row, width, target);
            seen[slot] = true;
        }
    }
    for (std::size_t k = 0; k < slotOfReceived_.size(); ++k)
    {
        std::copy_n(&combined[width*slotOfReceived_[k]], width, &received[width*k]);
    }
    MPI_Alltoallv(received.data(), receiveCounts.data(), receiveOffsets.data(), type,
                  sent.data(), sendCounts.data(), sendOffsets.data(), type, MPI_COMM_WORLD);
    for (std::size_t k = 0; k < sendOrder_.size(); ++k)
    {
        std::copy_n(&sent[width*k], width, &rows[width*sendOrder_[k]]);
    }
}


void particleRowExchange::sum(std::vector<double>& rows, int width) const
{
    combine(rows, width, [](double a, double b) { return a + b; });
}


void particleRowExchange::min(std::vector<int>& rows, int width) const
{
    combine(rows, width, [](int a, int b) { return std::min(a, b); });
}

} // namespace iceCoupling
} // namespace Foam
