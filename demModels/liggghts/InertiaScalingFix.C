#include "InertiaScalingFix.H"

#include "LiggghtsInstance.H"
#include "WaterForces.H"

#include "atom.h"
#include "fix_external.h"
#include "lammps.h"
#include "modify.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace iceDEM
{

InertiaScalingFix::InertiaScalingFix(LiggghtsInstance& lmp, double factor)
:
    lmp_(lmp),
    factor_(factor)
{
    if (!(factor >= 1.0) || !std::isfinite(factor))
    {
        throw std::logic_error("InertiaScalingFix: the factor must be a finite number >= 1");
    }
}


void InertiaScalingFix::define()
{
    if (factor_ == 1.0 || defined_)
    {
        return;
    }
    lmp_.command(std::string("fix ") + fixId + " all external pf/callback 1 1");
    static_cast<LAMMPS_NS::FixExternal&>(lmp_.fix(fixId)).set_callback(&InertiaScalingFix::callback, this);
    defined_ = true;
    const std::string problem = orderProblem();
    if (!problem.empty())
    {
        throw std::logic_error(problem);
    }
}


std::string InertiaScalingFix::orderProblem() const
{
    const LAMMPS_NS::Modify& modify = *lmp_.engine().modify;
    int own = -1;
    for (int k = 0; k < modify.nfix; ++k)
    {
        if (std::string(modify.fix[k]->id) == fixId) own = k;
    }
    if (own < 0)
    {
        return "";
    }
    for (int k = own + 1; k < modify.nfix; ++k)
    {
        const std::string id = modify.fix[k]->id;
        // The added mass scales the force too: the order of two scalings does not matter.
        if (id != WaterForces::addedMassFixId && (modify.fmask[k] & LAMMPS_NS::FixConst::POST_FORCE))
        {
            return "fix " + id + " adds forces after fix " + std::string(fixId)
                + ", which must be the last (it divides the total force and torque by the inertia factor)";
        }
    }
    return "";
}


void InertiaScalingFix::callback(void* self, int64_t, int, int*, double**, double** fexternal)
{
    static_cast<InertiaScalingFix*>(self)->apply(fexternal);
}


void InertiaScalingFix::apply(double** fexternal)
{
    LAMMPS_NS::LAMMPS& engine = lmp_.engine();
    if (engine.modify->nfix != checkedFixCount_)
    {
        checkedFixCount_ = engine.modify->nfix;
        const std::string problem = orderProblem();
        if (!problem.empty() && failure_.empty())
        {
            failure_ = problem;
        }
    }
    LAMMPS_NS::Atom& atom = *engine.atom;
    const double s = factor_;
    for (int i = 0; i < atom.nlocal; ++i)
    {
        for (int k = 0; k < 3; ++k)
        {
            fexternal[i][k] = 0.0;      // FixExternal adds it to the force
            atom.f[i][k] /= s;
            atom.torque[i][k] /= s;
        }
    }
}

} // namespace iceDEM
