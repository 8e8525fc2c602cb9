#include "RigidSheet.H"

#include "LiggghtsInstance.H"
#include "ParticleGather.H"

#include "atom.h"
#include "fix_external.h"
#include "lammps.h"
#include "update.h"

#include <cmath>

namespace iceDEM
{

RigidSheet::RigidSheet(LiggghtsInstance& lmp, long firstTag, double downwardLoad, double dampingAlpha)
:
    lmp_(lmp),
    firstTag_(firstTag),
    downwardLoad_(downwardLoad),
    dampingAlpha_(dampingAlpha)
{}


void RigidSheet::define()
{
    const LAMMPS_NS::Atom& atom = *lmp_.engine().atom;
    double local = 0.0;
    for (int i = 0; i < atom.nlocal; ++i)
    {
        if (atom.tag[i] >= firstTag_) local += atom.rmass[i];
    }
    mass_ = sumOverRanks(lmp_.communicator(), local);
    speed_ = netForce_ = travel_ = 0.0;
    lmp_.command(std::string("fix ") + fixId + " all external pf/callback 1 1");
    static_cast<LAMMPS_NS::FixExternal&>(lmp_.fix(fixId)).set_callback(&RigidSheet::callback, this);
}


void RigidSheet::release()
{
    lmp_.command(std::string("unfix ") + fixId);
    LAMMPS_NS::Atom& atom = *lmp_.engine().atom;
    for (int i = 0; i < atom.nlocal; ++i)
    {
        if (atom.tag[i] >= firstTag_) atom.v[i][2] = 0.0;
    }
    speed_ = 0.0;
}


void RigidSheet::callback(void* self, int64_t, int, int*, double**, double** fexternal)
{
    static_cast<RigidSheet*>(self)->move(fexternal);
}


void RigidSheet::move(double** fexternal)
{
    LAMMPS_NS::Atom& atom = *lmp_.engine().atom;
    for (int i = 0; i < atom.nlocal; ++i)
    {
        fexternal[i][0] = fexternal[i][1] = fexternal[i][2] = 0.0;
    }
    netForce_ = netForceOnTagsFrom(lmp_, lmp_.communicator(), firstTag_, 2) - downwardLoad_;
    const double dt = lmp_.engine().update->dt;
    const double damping = speed_ == 0.0 ? 0.0 : dampingAlpha_ * std::abs(netForce_) * (speed_ > 0.0 ? 1.0 : -1.0);
    speed_ += (netForce_ - damping) / mass_ * dt;
    const double dz = speed_ * dt;
    travel_ += dz;
    for (int i = 0; i < atom.nlocal; ++i)
    {
        if (atom.tag[i] >= firstTag_)
        {
            atom.x[i][2] += dz;
            atom.v[i][2] = speed_;
        }
    }
}

} // namespace iceDEM
