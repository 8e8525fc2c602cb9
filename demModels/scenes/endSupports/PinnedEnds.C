#include "PinnedEnds.H"

#include "Dictionary.H"
#include "Format.H"
#include "LiggghtsInstance.H"
#include "SceneContext.H"

#include "atom.h"
#include "lammps.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace iceDEM
{

PinnedEnds::PinnedEnds(const Dictionary& d)
:
    EndSupport(d, "pinned")
{}


std::string PinnedEnds::description() const
{
    std::ostringstream s;
    s << "pinned: each end pad turns as a rigid body about a hinge at x = " << hingeX_[0] << " and "
      << hingeX_[1] << " m (" << padParticles_[0] << " and " << padParticles_[1] << " particles, moments of inertia "
      << inertia_[0] << " and " << inertia_[1] << " kg m2)";
    return s.str();
}


Json PinnedEnds::summary() const
{
    Json j = EndSupport::summary();
    j["hinge_x_m"] = {hingeX_[0], hingeX_[1]};
    j["hinge_load_axis_coordinate_m"] = {hingeLoad_[0], hingeLoad_[1]};
    j["pad_particles"] = {padParticles_[0], padParticles_[1]};
    return j;
}


void PinnedEnds::defineForces(LiggghtsInstance& lmp, const SceneContext&, const EndSupportGeometry& g)
{
    const int L = g.loadAxis;
    handedness_ = L == 1 ? 1 : -1;
    // The hinges from the particles as the loading starts (the same on a
    // resume: the scene gives the starting positions, not the current ones).
    std::array<double, 2> mass{}, moment{};
    slotOfTag_.assign(g.particles.size(), -1);
    for (int e = 0; e < 2; ++e)
    {
        hingeX_[e] = g.supportX[e];
        padParticles_[e] = 0;
    }
    long slots = 0;
    for (int e = 0; e < 2; ++e)
    {
        for (std::size_t k = 0; k < g.particles.size(); ++k)
        {
            if (g.endOfTag[k] != e) continue;
            const ParticleSpec& p = g.particles[k];
            const double m = g.density * 4.0 / 3.0 * M_PI * p.radius * p.radius * p.radius;
            mass[e] += m;
            moment[e] += m * p.position[L];
            slotOfTag_[k] = slots++;
            ++padParticles_[e];
        }
        if (padParticles_[e] == 0)
        {
            throw std::runtime_error("endSupport pinned: the end pad at x = " + formatNumber(g.supportX[e])
                + " m has no particles");
        }
        hingeLoad_[e] = moment[e] / mass[e];
        inertia_[e] = 0.0;
    }
    for (std::size_t k = 0; k < g.particles.size(); ++k)
    {
        const int e = g.endOfTag[k];
        if (e < 0) continue;
        const ParticleSpec& p = g.particles[k];
        const double m = g.density * 4.0 / 3.0 * M_PI * p.radius * p.radius * p.radius;
        const double dx = p.position.x() - hingeX_[e], dl = p.position[L] - hingeLoad_[e];
        inertia_[e] += m * (dx * dx + dl * dl) + 0.4 * m * p.radius * p.radius;
    }
    torques_.assign(slots, 0.0);
    summed_.assign(slots, 0.0);

    // The pads' angular velocity, from their particles' spins (all equal; a
    // resumed run reads them from the restart).
    const LAMMPS_NS::Atom& atom = *lmp.engine().atom;
    const int h = g.hingeAxis();
    double local[2] = {-HUGE_VAL, -HUGE_VAL};
    for (int i = 0; i < atom.nlocal; ++i)
    {
        const int e = g.endOfTag[atom.tag[i] - 1];
        if (e >= 0) local[e] = std::max(local[e], atom.omega[i][h]);
    }
    double global[2];
    MPI_Allreduce(local, global, 2, MPI_DOUBLE, MPI_MAX, lmp.communicator());
    omega_ = {global[0], global[1]};
}


void PinnedEnds::afterForces(LiggghtsInstance& lmp, const EndSupportGeometry& g)
{
    LAMMPS_NS::Atom& atom = *lmp.engine().atom;
    const int L = g.loadAxis, h = g.hingeAxis();
    const double s = handedness_;
    std::fill(torques_.begin(), torques_.end(), 0.0);
    for (int i = 0; i < atom.nlocal; ++i)
    {
        const int tag = atom.tag[i] - 1;
        const int e = g.endOfTag[tag];
        if (e < 0) continue;
        const double dx = atom.x[i][0] - hingeX_[e], dl = atom.x[i][L] - hingeLoad_[e];
        torques_[slotOfTag_[tag]] = s * (dx * atom.f[i][L] - dl * atom.f[i][0]) + atom.torque[i][h];
    }
    MPI_Allreduce(torques_.data(), summed_.data(), static_cast<int>(summed_.size()), MPI_DOUBLE, MPI_SUM,
                  lmp.communicator());
    const double dt = lmp.timeStep();
    std::array<double, 2> c{}, sn{};
    std::size_t slot = 0;
    for (int e = 0; e < 2; ++e)
    {
        double torque = 0.0;
        for (long k = 0; k < padParticles_[e]; ++k) torque += summed_[slot++];
        omega_[e] += dt * torque / inertia_[e];
        c[e] = std::cos(omega_[e] * dt);
        sn[e] = s * std::sin(omega_[e] * dt);
    }
    for (int i = 0; i < atom.nlocal; ++i)
    {
        const int e = g.endOfTag[atom.tag[i] - 1];
        if (e < 0) continue;
        const double dx = atom.x[i][0] - hingeX_[e], dl = atom.x[i][L] - hingeLoad_[e];
        const double nx = c[e] * dx - sn[e] * dl, nl = sn[e] * dx + c[e] * dl;
        atom.x[i][0] = hingeX_[e] + nx;
        atom.x[i][L] = hingeLoad_[e] + nl;
        atom.v[i][0] = -s * omega_[e] * nl;
        atom.v[i][L] = s * omega_[e] * nx;
        atom.v[i][h] = 0.0;
        atom.omega[i][0] = atom.omega[i][1] = atom.omega[i][2] = 0.0;
        atom.omega[i][h] = omega_[e];
    }
}

} // namespace iceDEM
