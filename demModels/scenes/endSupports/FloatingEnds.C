#include "FloatingEnds.H"

#include "Dictionary.H"
#include "Format.H"
#include "LiggghtsInstance.H"
#include "SceneContext.H"

#include "atom.h"
#include "fix_external.h"
#include "lammps.h"

#include <sstream>
#include <stdexcept>

namespace iceDEM
{

FloatingEnds::FloatingEnds(const Dictionary& d)
:
    EndSupport(d, "floating")
{
    if (!d.isDict("floatingCoeffs"))
    {
        d.fail("floatingCoeffs", "missing: endSupport floating needs floatingCoeffs { stiffness <N/m>; } "
               "(the horizontal spring on each end pad)");
    }
    const Dictionary& c = d.subDict("floatingCoeffs");
    c.checkKeys({"stiffness"});
    stiffness_ = c.getScalar("stiffness");
    if (!(stiffness_ >= 0.0))
    {
        c.fail("stiffness", formatNumber(stiffness_) + " is not allowed: expected N/m per end, 0 or more");
    }
}


std::string FloatingEnds::description() const
{
    std::ostringstream s;
    s << "floating: the ends held by the water and a horizontal spring of " << stiffness_ << " N/m on each end pad ("
      << padParticles_[0] << " and " << padParticles_[1] << " particles)";
    return s.str();
}


Json FloatingEnds::summary() const
{
    Json j = EndSupport::summary();
    j["spring_stiffness_N_per_m"] = stiffness_;
    j["pad_particles"] = {padParticles_[0], padParticles_[1]};
    return j;
}


void FloatingEnds::defineForces(LiggghtsInstance& lmp, const SceneContext&, const EndSupportGeometry& g)
{
    for (int e = 0; e < 2; ++e)
    {
        padParticles_[e] = g.padParticles(e);
        if (padParticles_[e] == 0)
        {
            throw std::runtime_error("endSupport floating: the end pad at x = " + formatNumber(g.supportX[e])
                + " m has no particles");
        }
    }
    lmp_ = &lmp;
    springGeometry_ = &g;
    lmp.command("fix endSupportSprings all external pf/callback 1 1");
    static_cast<LAMMPS_NS::FixExternal&>(lmp.fix("endSupportSprings")).set_callback(&FloatingEnds::springCallback, this);
}


void FloatingEnds::springCallback(void* self, int64_t, int nlocal, int*, double**, double** fexternal)
{
    auto& me = *static_cast<FloatingEnds*>(self);
    const EndSupportGeometry& g = *me.springGeometry_;
    const LAMMPS_NS::Atom& atom = *me.lmp_->engine().atom;
    const double k[2] = {me.stiffness_ / me.padParticles_[0], me.stiffness_ / me.padParticles_[1]};
    double load = 0.0;
    for (int i = 0; i < nlocal; ++i)
    {
        fexternal[i][0] = fexternal[i][1] = fexternal[i][2] = 0.0;
        const int tag = atom.tag[i] - 1;
        const int e = g.endOfTag[tag];
        if (e < 0) continue;
        const Vec3& anchor = g.particles[tag].position;
        for (int c = 0; c < 2; ++c)     // horizontal: x and y
        {
            fexternal[i][c] = -k[e] * (atom.x[i][c] - anchor[c]);
        }
        load += fexternal[i][g.loadAxis];
    }
    me.springLoad_ = load;
}


double FloatingEnds::localReaction(const LiggghtsInstance&, const EndSupportGeometry& g) const
{
    // The springs push the pads; against the platen is -pushSign.
    return -g.pushSign * springLoad_;
}

} // namespace iceDEM
