// Bonded pairs have no LIGGGHTS contact (physics.md section 2), and a pair
// whose bond broke gets one at the next step. Two spheres 1 mm into each
// other, bonded there (so the bond's rest length is their distance), the
// second sliding sideways; no integrator, so the geometry stays put:
//
// 1. while bonded, the force on a sphere is the bond's shear spring alone,
//    K_s times the bond's shear displacement: a contact would add its own
//    tangential spring, and its normal spring k_n * overlap = 200 N;
// 2. once the bond breaks in shear, one step later the pair pushes apart
//    with the contact's k_n * overlap exactly (hooke/stiffness, no damping).
//
// On two ranks the spheres sit on either side of the ranks' boundary.
//
// usage: mpirun -np N bondedContacts

#include "BondBuilder.H"
#include "GranularBox.H"
#include "IceBondForces.H"
#include "LiggghtsInstance.H"

#include "atom.h"
#include "lammps.h"

#include <mpi.h>

#include <cmath>
#include <iostream>
#include <sstream>
#include <string>

using namespace iceDEM;

namespace
{

constexpr double radius = 0.01;
constexpr double overlap = 0.001;
constexpr double contactNormalStiffness = 2.0e5;
constexpr double slidingSpeed = 0.1;

int failures = 0;

void check(bool ok, const std::string& what)
{
    int rank = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    std::cout << "rank " << rank << (ok ? ": ok   " : ": FAIL ") << what << std::endl;
    failures += !ok;
}

bool relativelyEqual(double a, double b, double tolerance)
{
    return std::abs(a - b) <= tolerance * std::max(std::abs(a), std::abs(b));
}

} // namespace


int main(int argc, char** argv)
{
    MPI_Init(&argc, &argv);

    IceProperties ice;
    ice.material.youngsModulus = 1e7;
    for (BondFamilyParameters& f : ice.families)
    {
        f.youngsModulus = 1e7;
        f.breakN = 1e-3;
    }
    ice.damping.model = DampingModel::none;

    std::vector<ParticleSpec> particles(2);
    particles[0].position = Vec3(-0.5 * (2.0 * radius - overlap), 0.0, 0.0);
    particles[1].position = Vec3(0.5 * (2.0 * radius - overlap), 0.0, 0.0);
    for (ParticleSpec& p : particles) p.radius = radius;
    const std::vector<BondPair> pairs = BondBuilder(ice).build(particles);
    const double shearStiffness = BondStiffness::of(ice.family(BondFamily::ice), radius, radius).shear;

    {
        LiggghtsInstance lmp(MPI_COMM_WORLD, "none");
        setUpGranularBox(lmp, "-0.1 0.1 -0.1 0.1 -0.1 0.1", contactNormalStiffness, particles);

        IceBondForces bonds(lmp, ice);
        lmp.command("fix iceBondForces all external pf/callback 1 1");
        bonds.attach("iceBondForces");
        lmp.command("run 0");   // LIGGGHTS' first set-up resets property/atom values
        bonds.createBonds(particles, pairs);
        bonds.suspendBreakage(true);

        LAMMPS_NS::Atom& atom = *lmp.engine().atom;
        for (int i = 0; i < atom.nlocal; ++i)
        {
            atom.v[i][1] = atom.tag[i] == 2 ? slidingSpeed : 0.0;
        }
        lmp.command("run 20");

        // 1. Bonded: the shear spring alone.
        double shearDisplacement = 0.0;
        for (const BondState& s : bonds.localBondStates())
        {
            shearDisplacement = s.shearDisplacement.norm();
        }
        MPI_Allreduce(MPI_IN_PLACE, &shearDisplacement, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
        for (int i = 0; i < atom.nlocal; ++i)
        {
            std::ostringstream what;
            what << "bonded, particle " << atom.tag[i] << ": force (" << atom.f[i][0] << ", " << atom.f[i][1]
                 << ") N = the bond's shear spring " << shearStiffness * shearDisplacement
                 << " N along y, nothing along x (a contact would add " << contactNormalStiffness * overlap << " N)";
            check(shearDisplacement > 0.0 && std::abs(atom.f[i][0]) < 1e-9
                  && relativelyEqual(std::abs(atom.f[i][1]), shearStiffness * shearDisplacement, 1e-9),
                  what.str());
        }

        // 2. Broken: the contact acts from the next step.
        bonds.suspendBreakage(false);
        long broken = 0;
        int steps = 0;
        for (; steps < 2000 && broken == 0; ++steps)
        {
            lmp.command("run 1 pre no post no");
            broken = static_cast<long>(bonds.takeLocalBreakEvents().size());
            MPI_Allreduce(MPI_IN_PLACE, &broken, 1, MPI_LONG, MPI_SUM, MPI_COMM_WORLD);
        }
        check(broken == 1, "the bond broke in shear after " + std::to_string(steps) + " more steps");
        lmp.command("run 1 pre no post no");
        for (int i = 0; i < atom.nlocal; ++i)
        {
            const double expected = (atom.tag[i] == 1 ? -1.0 : 1.0) * contactNormalStiffness * overlap;
            std::ostringstream what;
            what << "one step after the break, particle " << atom.tag[i] << ": normal force " << atom.f[i][0]
                 << " N = k_n * overlap " << expected << " N";
            check(relativelyEqual(atom.f[i][0], expected, 1e-9), what.str());
        }
    }

    MPI_Allreduce(MPI_IN_PLACE, &failures, 1, MPI_INT, MPI_SUM, MPI_COMM_WORLD);
    MPI_Finalize();
    return failures == 0 ? 0 : 1;
}
