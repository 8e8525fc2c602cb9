#include "BondNetworkFrame.H"

namespace iceDEM
{

BondNetworkFrame::BondNetworkFrame
(
    const ParticleFrame& particles,
    const std::map<long, std::size_t>& indexOfTag
)
:
    particles_(particles),
    indexOfTag_(indexOfTag)
{
    frame_.points = particles.position;
}


long BondNetworkFrame::rowOf(long tag) const
{
    const auto found = indexOfTag_.find(tag);
    return found == indexOfTag_.end() ? -1 : static_cast<long>(found->second);
}


void BondNetworkFrame::addIntact(long tagA, long tagB, int family)
{
    const long a = rowOf(tagA);
    const long b = rowOf(tagB);
    if (a < 0 || b < 0)
    {
        return;
    }
    frame_.ends.push_back({a, b});
    frame_.family.push_back(family);
    frame_.state.push_back(0);
    frame_.mode.push_back(0);
    frame_.time.push_back(-1.0);
}


void BondNetworkFrame::addBroken(const BreakEvent& event)
{
    // The centre divides the bond as the radii do (BondKernelBody.H); halves if a
    // particle's radius is not in the frame.
    double shareOfA = 0.5;
    const long a = rowOf(event.tagA);
    const long b = rowOf(event.tagB);
    if (a >= 0 && b >= 0 && !particles_.radius.empty())
    {
        shareOfA = particles_.radius[a]/(particles_.radius[a] + particles_.radius[b]);
    }
    const Vec3 endA = event.position - shareOfA*event.separation;
    const long first = static_cast<long>(frame_.points.size());
    frame_.points.push_back(endA);
    frame_.points.push_back(endA + event.separation);
    frame_.ends.push_back({first, first + 1});
    frame_.family.push_back(static_cast<int>(event.family));
    frame_.state.push_back(1);
    frame_.mode.push_back(static_cast<int>(event.mode));
    frame_.time.push_back(event.time);
}

} // namespace iceDEM
