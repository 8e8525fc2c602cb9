#include "SimpleEnds.H"

#include "Dictionary.H"
#include "Format.H"
#include "LiggghtsInstance.H"
#include "SceneContext.H"

#include "atom.h"
#include "fix_external.h"
#include "lammps.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace iceDEM
{

SimpleEnds::SimpleEnds(const Dictionary& d)
:
    EndSupport(d, "simple")
{}


std::string SimpleEnds::description() const
{
    std::ostringstream s;
    s << "simple: frictionless rollers of " << 2.0 * radius_ << " m diameter, axes at x = " << axisX_[0]
      << " and " << axisX_[1] << " m, touching the body";
    return s.str();
}


Json SimpleEnds::summary() const
{
    Json j = EndSupport::summary();
    j["roller_x_m"] = {axisX_[0], axisX_[1]};
    j["roller_axis_load_axis_coordinate_m"] = {axisLoad_[0], axisLoad_[1]};
    j["roller_diameter_m"] = 2.0 * radius_;
    return j;
}


void SimpleEnds::defineForces(LiggghtsInstance& lmp, const SceneContext&, const EndSupportGeometry& g)
{
    const int L = g.loadAxis;
    const int side = g.pushSign;    // the rollers are where the platen pushes the body to
    radius_ = 0.5 * g.rollerDiameter;
    if (!(g.contactStiffness > 0.0))
    {
        throw std::logic_error("endSupport simple: the scene gave no contact stiffness");
    }
    // Placed touching the body as the loading starts (from the starting
    // positions: the same on a resume).
    for (int e = 0; e < 2; ++e)
    {
        axisX_[e] = g.supportX[e];
        double touching = -side * HUGE_VAL;
        for (const ParticleSpec& p : g.particles)
        {
            const double reach = radius_ + p.radius;
            const double dx = p.position.x() - axisX_[e];
            if (std::abs(dx) < reach)
            {
                const double t = p.position[L] + side * std::sqrt(reach * reach - dx * dx);
                touching = side > 0 ? std::max(touching, t) : std::min(touching, t);
            }
        }
        if (!std::isfinite(touching))
        {
            throw std::runtime_error("endSupport simple: no particle near the support line x = "
                + formatNumber(axisX_[e]) + " m");
        }
        axisLoad_[e] = touching;
    }
    lmp_ = &lmp;
    rollerGeometry_ = &g;
    lmp.command("fix endSupportRollers all external pf/callback 1 1");
    static_cast<LAMMPS_NS::FixExternal&>(lmp.fix("endSupportRollers")).set_callback(&SimpleEnds::contactCallback, this);
}


void SimpleEnds::contactCallback(void* self, int64_t, int nlocal, int*, double**, double** fexternal)
{
    auto& me = *static_cast<SimpleEnds*>(self);
    const EndSupportGeometry& g = *me.rollerGeometry_;
    const LAMMPS_NS::Atom& atom = *me.lmp_->engine().atom;
    const int L = g.loadAxis;
    double load = 0.0;
    for (int i = 0; i < nlocal; ++i)
    {
        fexternal[i][0] = fexternal[i][1] = fexternal[i][2] = 0.0;
        for (int e = 0; e < 2; ++e)
        {
            const double dx = atom.x[i][0] - me.axisX_[e], dl = atom.x[i][L] - me.axisLoad_[e];
            const double reach = me.radius_ + atom.radius[i];
            const double d2 = dx * dx + dl * dl;
            if (d2 >= reach * reach || d2 == 0.0) continue;
            const double d = std::sqrt(d2);
            const double nx = dx / d, nl = dl / d;
            const double vn = atom.v[i][0] * nx + atom.v[i][L] * nl;
            const double force = std::max(0.0, g.contactStiffness * (reach - d) - g.contactDamping * vn);
            fexternal[i][0] += force * nx;
            fexternal[i][L] += force * nl;
            load += force * nl;
        }
    }
    me.rollerLoad_ = load;
}


double SimpleEnds::localReaction(const LiggghtsInstance&, const EndSupportGeometry& g) const
{
    // The rollers push the body back against the platen: towards -pushSign.
    return -g.pushSign * rollerLoad_;
}

} // namespace iceDEM
