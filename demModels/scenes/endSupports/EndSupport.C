#include "EndSupport.H"

#include "ClampedEnds.H"
#include "Dictionary.H"
#include "FloatingEnds.H"
#include "InputError.H"
#include "LiggghtsInstance.H"
#include "PinnedEnds.H"
#include "SelectionTable.H"
#include "SimpleEnds.H"

#include <algorithm>

#include "atom.h"
#include "fix_external.h"
#include "lammps.h"
#include "update.h"

namespace iceDEM
{

namespace
{

using EndSupports = SelectionTable<EndSupport, const Dictionary&>;

const EndSupports endSupports
{{
    {"clamped", &EndSupports::construct<ClampedEnds>},
    {"pinned", &EndSupports::construct<PinnedEnds>},
    {"simple", &EndSupports::construct<SimpleEnds>},
    {"floating", &EndSupports::construct<FloatingEnds>},
}};

} // namespace


long EndSupportGeometry::padParticles(int end) const
{
    long n = 0;
    for (int e : endOfTag) n += e == end;
    return n;
}


std::unique_ptr<EndSupport> EndSupport::New(const Dictionary& d)
{
    return endSupports.New(d, "endSupport", d);
}


std::unique_ptr<EndSupport> EndSupport::New
(
    const Dictionary& d,
    const std::vector<std::string>& allowed,
    const std::string& why
)
{
    const std::string name = d.getChoice("endSupport", names());
    if (std::find(allowed.begin(), allowed.end(), name) == allowed.end())
    {
        std::string list;
        for (const std::string& a : allowed) list += " " + a;
        d.fail("endSupport", "'" + name + "' is not available here: " + why + "; allowed here:" + list);
    }
    return New(d);
}


const std::vector<std::string>& EndSupport::names()
{
    return endSupports.names();
}


EndSupport::EndSupport(const Dictionary& d, const std::string&)
:
    fileName_(d.fileName())
{}


EndSupport::~EndSupport() = default;


std::string EndSupport::description() const
{
    return name();
}


Json EndSupport::summary() const
{
    Json j;
    j["type"] = name();
    return j;
}


void EndSupport::defineForces(LiggghtsInstance&, const SceneContext&, const EndSupportGeometry&)
{}


void EndSupport::defineMotion(LiggghtsInstance& lmp, const EndSupportGeometry& geometry)
{
    lmp_ = &lmp;
    geometry_ = &geometry;
    lmp.command("fix endSupport all external pf/callback 1 1");
    static_cast<LAMMPS_NS::FixExternal&>(lmp.fix("endSupport")).set_callback(&EndSupport::callback, this);
}


double EndSupport::reaction(MPI_Comm comm)
{
    double local[2] = {reactionSum_, static_cast<double>(reactionSteps_)};
    double total[2];
    MPI_Allreduce(local, total, 2, MPI_DOUBLE, MPI_SUM, comm);
    int ranks = 1;
    MPI_Comm_size(comm, &ranks);
    reactionSum_ = 0.0;
    reactionSteps_ = 0;
    const double steps = total[1] / ranks;
    return steps > 0.0 ? total[0] / steps : 0.0;
}


double EndSupport::localReaction(const LiggghtsInstance& lmp, const EndSupportGeometry& g) const
{
    return padForce(lmp, g);
}


double EndSupport::padForce(const LiggghtsInstance& lmp, const EndSupportGeometry& g)
{
    // The body pushes its pads towards pushSign; what holds them pushes back.
    const LAMMPS_NS::Atom& atom = *lmp.engine().atom;
    double sum = 0.0;
    for (int i = 0; i < atom.nlocal; ++i)
    {
        if (g.endOfTag[atom.tag[i] - 1] >= 0)
        {
            sum += atom.f[i][g.loadAxis];
        }
    }
    return g.pushSign * sum;
}


void EndSupport::callback(void* self, int64_t, int nlocal, int*, double**, double** fexternal)
{
    for (int i = 0; i < nlocal; ++i)
    {
        fexternal[i][0] = fexternal[i][1] = fexternal[i][2] = 0.0;
    }
    auto& support = *static_cast<EndSupport*>(self);
    // LIGGGHTS' set-up (`run 0`, a run's start) computes the forces again
    // without a step: nothing moves and nothing is counted then.
    if (support.lmp_->engine().update->setupflag)
    {
        return;
    }
    support.reactionSum_ += support.localReaction(*support.lmp_, *support.geometry_);
    ++support.reactionSteps_;
    support.afterForces(*support.lmp_, *support.geometry_);
}


} // namespace iceDEM
