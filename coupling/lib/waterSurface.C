#include "waterSurface.H"

namespace Foam
{
namespace iceCoupling
{

waterSurface::waterSurface(const fvMesh& mesh, const dictionary& couplingProperties)
:
    active_(couplingProperties.found("waterLevel")),
    level_(couplingProperties.getOrDefault<scalar>("waterLevel", GREAT))
{
    if (active_)
    {
        const boundBox& box = mesh.bounds();
        if (mag(box.max().z() - level_) > 1e-9*box.mag())
        {
            FatalIOErrorInFunction(couplingProperties)
                << "entry 'waterLevel' is " << level_ << " m: the fluid mesh must end at the"
                << " water surface, but its top is at z = " << box.max().z() << " m"
                << " (system/blockMeshDict)" << exit(FatalIOError);
        }
    }
}


scalar waterSurface::submergedFraction(const ::iceCoupling::CouplingParticle& p) const
{
    if (!active_)
    {
        return 1;
    }
    const scalar r = 0.5*p.diameter;
    const scalar h = min(max(level_ - (p.position[2] - r), scalar(0)), 2*r);
    return sqr(h)*(3*r - h)/(4*pow3(r));
}


::iceCoupling::CouplingParticle waterSurface::inWater(const ::iceCoupling::CouplingParticle& p) const
{
    ::iceCoupling::CouplingParticle wet(p);
    if (active_)
    {
        wet.position[2] = min(p.position[2], level_ - 1e-6*p.diameter);
    }
    return wet;
}

} // namespace iceCoupling
} // namespace Foam
