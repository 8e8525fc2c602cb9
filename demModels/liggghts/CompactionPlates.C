#include "CompactionPlates.H"

#include "LiggghtsInstance.H"

#include "atom.h"
#include "fix_external.h"
#include "lammps.h"
#include "update.h"

#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace iceDEM
{

CompactionPlates::CompactionPlates(LiggghtsInstance& lmp, const CompactionPlateLaw& law)
:
    lmp_(lmp),
    law_(law)
{}


void CompactionPlates::define()
{
    lmp_.command(std::string("fix ") + fixId + " all external pf/callback 1 1");
    static_cast<LAMMPS_NS::FixExternal&>(lmp_.fix(fixId)).set_callback(&CompactionPlates::callback, this);
}


void CompactionPlates::place(double bottom, double top)
{
    close(bottom, top, bottom, top, 0.0);
}


void CompactionPlates::close(double bottom, double top, double finalBottom, double finalTop, double speed)
{
    if (!(bottom < top) || !(finalBottom < finalTop) || speed < 0.0)
    {
        throw std::logic_error("CompactionPlates::close: needs bottom < top, finalBottom < finalTop, speed >= 0");
    }
    startBottom_ = bottom_ = bottom;
    startTop_ = top_ = top;
    finalBottom_ = finalBottom;
    finalTop_ = finalTop;
    const double travel = std::max(std::abs(finalBottom - bottom), std::abs(finalTop - top));
    duration_ = travel > 0.0 ? travel/speed : 0.0;
    if (travel > 0.0 && !(speed > 0.0))
    {
        throw std::logic_error("CompactionPlates::close: the plates have to move, at no speed");
    }
    startStep_ = lmp_.step();
    bottomVelocity_ = topVelocity_ = 0.0;
    closed_ = duration_ == 0.0;
    active_ = true;
}


void CompactionPlates::callback(void* self, int64_t step, int, int*, double**, double** fexternal)
{
    static_cast<CompactionPlates*>(self)->addForces(static_cast<long>(step), fexternal);
}


void CompactionPlates::addForces(long step, double** fexternal)
{
    const LAMMPS_NS::Atom& atom = *lmp_.engine().atom;
    local_ = PlateLoads();
    if (active_ && !closed_)
    {
        const double t = static_cast<double>(step - startStep_)*lmp_.engine().update->dt;
        closed_ = t >= duration_;
        const double fraction = closed_ ? 1.0 : t/duration_;
        bottom_ = startBottom_ + fraction*(finalBottom_ - startBottom_);
        top_ = startTop_ + fraction*(finalTop_ - startTop_);
        bottomVelocity_ = closed_ ? 0.0 : (finalBottom_ - startBottom_)/duration_;
        topVelocity_ = closed_ ? 0.0 : (finalTop_ - startTop_)/duration_;
    }
    for (int i = 0; i < atom.nlocal; ++i)
    {
        fexternal[i][0] = fexternal[i][1] = fexternal[i][2] = 0.0;
        if (!active_)
        {
            continue;
        }
        const double f = law_.force(atom.x[i][2], atom.v[i][2], atom.radius[i], bottom_, top_, bottomVelocity_, topVelocity_);
        if (f == 0.0)
        {
            continue;
        }
        fexternal[i][2] = f;
        ++local_.touching;
        if (f > 0.0)
        {
            local_.floor += f;
        }
        else
        {
            local_.lid -= f;
            ++local_.touchingLid;
        }
    }
}


void CompactionPlates::backOffLid(double targetLoad, double minTop)
{
    const PlateLoads now = loads();
    if (now.touchingLid > 0)
    {
        const double lid = top_ + (now.lid - targetLoad)/(double(now.touchingLid)*law_.normalStiffness);
        place(bottom_, std::max(minTop, lid));
    }
}


PlateLoads CompactionPlates::loads() const
{
    double local[4] = {local_.floor, local_.lid, double(local_.touching), double(local_.touchingLid)};
    double sum[4];
    MPI_Allreduce(local, sum, 4, MPI_DOUBLE, MPI_SUM, lmp_.communicator());
    PlateLoads total;
    total.floor = sum[0];
    total.lid = sum[1];
    total.touching = static_cast<long>(sum[2]);
    total.touchingLid = static_cast<long>(sum[3]);
    return total;
}

} // namespace iceDEM
