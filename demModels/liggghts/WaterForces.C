#include "WaterForces.H"

#include "InertiaScalingFix.H"
#include "LiggghtsInstance.H"

#include "atom.h"
#include "fix_external.h"
#include "lammps.h"
#include "modify.h"

#include <cmath>
#include <cstring>
#include <sstream>
#include <stdexcept>

namespace iceDEM
{

WaterForces::WaterForces(LiggghtsInstance& lmp, const HydrostaticWater& water)
:
    lmp_(lmp),
    water_(water)
{}


void WaterForces::defineForceFix(const std::string& group)
{
    const LAMMPS_NS::Modify& modify = *lmp_.engine().modify;
    for (int k = 0; k < modify.nfix; ++k)
    {
        if (std::strcmp(modify.fix[k]->style, "external") == 0)
        {
            throw std::logic_error
            (
                std::string("fix ") + forceFixId + " must be defined before fix "
              + modify.fix[k]->id + ": the ice-bond fix damps the total force, water included"
            );
        }
    }
    lmp_.command(std::string("fix ") + forceFixId + " " + group + " external pf/callback 1 1");
    static_cast<LAMMPS_NS::FixExternal&>(lmp_.fix(forceFixId)).set_callback(&WaterForces::forceCallback, this);
    forceFixDefined_ = true;
}


void WaterForces::defineAddedMassFix()
{
    if (!forceFixDefined_)
    {
        throw std::logic_error("WaterForces::defineAddedMassFix called before defineForceFix");
    }
    if (water_.parameters().addedMassCoefficient <= 0.0)
    {
        return;
    }
    lmp_.command(std::string("fix ") + addedMassFixId + " all external pf/callback 1 1");
    static_cast<LAMMPS_NS::FixExternal&>(lmp_.fix(addedMassFixId)).set_callback(&WaterForces::addedMassCallback, this);
    addedMassFixDefined_ = true;
    const std::string problem = orderProblem();
    if (!problem.empty())
    {
        throw std::logic_error(problem);
    }
}


std::string WaterForces::orderProblem() const
{
    const LAMMPS_NS::Modify& modify = *lmp_.engine().modify;
    int forceFix = -1, addedMassFix = -1;
    for (int k = 0; k < modify.nfix; ++k)
    {
        const std::string id = modify.fix[k]->id;
        if (id == forceFixId) forceFix = k;
        if (id == addedMassFixId) addedMassFix = k;
    }
    for (int k = 0; k < modify.nfix; ++k)
    {
        const std::string id = modify.fix[k]->id;
        if (k < forceFix && std::strcmp(modify.fix[k]->style, "external") == 0)
        {
            return "fix " + std::string(forceFixId) + " comes after fix " + id
                + ": it must come first (the ice-bond fix damps the total force, water included)";
        }
        // The inertia scaling (InertiaScalingFix) scales the force too: the
        // order of two scalings does not matter.
        if (addedMassFixDefined_ && k > addedMassFix && id != InertiaScalingFix::fixId
         && (modify.fmask[k] & LAMMPS_NS::FixConst::POST_FORCE))
        {
            return "fix " + id + " adds forces after fix " + std::string(addedMassFixId)
                + ", which must be the last (it turns the total force into an acceleration with the added mass)";
        }
    }
    return "";
}


void WaterForces::forceCallback(void* self, int64_t, int, int*, double**, double** fexternal)
{
    static_cast<WaterForces*>(self)->addForces(fexternal);
}


void WaterForces::addedMassCallback(void* self, int64_t, int, int*, double**, double** fexternal)
{
    static_cast<WaterForces*>(self)->applyAddedMass(fexternal);
}


void WaterForces::addForces(double** fexternal)
{
    const LAMMPS_NS::Atom& atom = *lmp_.engine().atom;
    const int groupBit = lmp_.fix(forceFixId).groupbit;
    local_ = WaterForceTotals();
    for (int i = 0; i < atom.nlocal; ++i)
    {
        fexternal[i][0] = fexternal[i][1] = fexternal[i][2] = 0.0;
        if (!(atom.mask[i] & groupBit))
        {
            continue;
        }
        const Vec3 velocity(atom.v[i][0], atom.v[i][1], atom.v[i][2]);
        if (!std::isfinite(atom.x[i][2]) || !std::isfinite(velocity.squaredNorm()))
        {
            if (failure_.empty())
            {
                std::ostringstream msg;
                msg << "non-finite position or velocity of particle " << atom.tag[i] << " (step "
                    << lmp_.step() << ", time " << lmp_.time() << " s): the run has blown up";
                failure_ = msg.str();
            }
            continue;
        }
        const SphereWaterLoad load = water_.sphereLoad(atom.radius[i], atom.x[i][2], velocity);
        const Vec3 force = load.buoyancy + load.drag;
        for (int k = 0; k < 3; ++k)
        {
            fexternal[i][k] = force[k];   // FixExternal adds it to the atom's force
        }
        local_.buoyancy += load.buoyancy;
        local_.drag += load.drag;
        local_.submergedVolume += load.submergedVolume;
        local_.addedMass += load.addedMass;
    }
}


void WaterForces::applyAddedMass(double** fexternal)
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
    const int groupBit = lmp_.fix(forceFixId).groupbit;
    const double surface = water_.parameters().surfaceLevel;
    const double coefficient = water_.parameters().addedMassCoefficient * water_.parameters().density;
    for (int i = 0; i < atom.nlocal; ++i)
    {
        fexternal[i][0] = fexternal[i][1] = fexternal[i][2] = 0.0;
        if (!(atom.mask[i] & groupBit))
        {
            continue;
        }
        const double r = atom.radius[i];
        const double addedMass = coefficient * submergedSphereVolume(r, surface - (atom.x[i][2] - r));
        if (addedMass > 0.0)
        {
            const double factor = water_.inertiaFactor(atom.rmass[i], addedMass);
            for (int k = 0; k < 3; ++k)
            {
                atom.f[i][k] *= factor;
            }
        }
    }
}


WaterForceTotals WaterForces::totals() const
{
    double local[8] =
    {
        local_.buoyancy.x(), local_.buoyancy.y(), local_.buoyancy.z(),
        local_.drag.x(), local_.drag.y(), local_.drag.z(),
        local_.submergedVolume, local_.addedMass
    };
    double sum[8];
    MPI_Allreduce(local, sum, 8, MPI_DOUBLE, MPI_SUM, lmp_.communicator());
    WaterForceTotals t;
    t.buoyancy = Vec3(sum[0], sum[1], sum[2]);
    t.drag = Vec3(sum[3], sum[4], sum[5]);
    t.submergedVolume = sum[6];
    t.addedMass = sum[7];
    return t;
}

} // namespace iceDEM
