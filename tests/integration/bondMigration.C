// A spinning, shearing block of bonded spheres flies across the boundary
// between two MPI ranks. Writes every particle's state and every bond's
// history at the end, for comparison between 1 and 2 ranks: bonds and their
// histories must travel with their atoms. With `resync`, the bond table is
// read and bonds are added (none) between the run chunks, as output and
// freeze-bond creation do: IceBondForces then copies its step list into the
// table and rebuilds it, which must change nothing.
//
// usage: mpirun -np N bondMigration OUTPUT.txt [resync]

#include "BondBuilder.H"
#include "GranularBox.H"
#include "IceBondForces.H"
#include "LiggghtsInstance.H"
#include "ParticleGather.H"

#include "atom.h"
#include "lammps.h"

#include <mpi.h>

#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <string>

using namespace iceDEM;

namespace
{

std::vector<ParticleSpec> fccBlock(double radius)
{
    std::vector<ParticleSpec> particles;
    const double a = 2.0 * radius * std::sqrt(2.0);
    const Vec3 basis[4] = {{0, 0, 0}, {0.5, 0.5, 0}, {0.5, 0, 0.5}, {0, 0.5, 0.5}};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            for (int k = 0; k < 3; ++k)
                for (const Vec3& b : basis)
                {
                    ParticleSpec p;
                    p.position = a * (Vec3(i, j, k) + b) + Vec3(-0.12, -0.04, -0.04);
                    p.radius = radius;
                    particles.push_back(p);
                }
    return particles;
}

} // namespace


int main(int argc, char** argv)
{
    MPI_Init(&argc, &argv);
    int rank = 0, ranks = 1;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &ranks);
    const bool resync = argc == 3 && std::string(argv[2]) == "resync";
    if (argc != 2 && !resync)
    {
        if (rank == 0) std::cerr << "usage: bondMigration OUTPUT.txt [resync]" << std::endl;
        MPI_Finalize();
        return 1;
    }

    IceProperties ice;
    ice.material.youngsModulus = 1e7;
    for (BondFamilyParameters& f : ice.families)
    {
        f.youngsModulus = 1e7;
        f.unbreakable = true;
    }
    ice.damping.model = DampingModel::none;

    const double radius = 0.01;
    const std::vector<ParticleSpec> particles = fccBlock(radius);
    BondBuilder builder(ice);
    const std::vector<BondPair> pairs = builder.build(particles);

    int status = 0;
    {
        LiggghtsInstance lmp(MPI_COMM_WORLD, "none");
        setUpGranularBox(lmp, "-0.3 0.3 -0.2 0.2 -0.2 0.2", 2.0e5, particles);

        IceBondForces bonds(lmp, ice);
        lmp.command("fix iceBondForces all external pf/callback 1 1");
        bonds.attach("iceBondForces");
        lmp.command("fix integrate all nve/sphere");
        lmp.command("run 0");   // LIGGGHTS' first set-up resets property/atom values
        bonds.createBonds(particles, pairs);

        // Fly along +x, spin about y and shear: every spring gets a history.
        LAMMPS_NS::Atom& atom = *lmp.engine().atom;
        for (int i = 0; i < atom.nlocal; ++i)
        {
            atom.v[i][0] = 1.0 + 2.0 * atom.x[i][1];
            atom.v[i][1] = 0.5 * atom.x[i][2];
            atom.v[i][2] = -0.3 * atom.x[i][0];
            atom.omega[i][0] = 3.0 * atom.x[i][2];
            atom.omega[i][1] = 5.0;
            atom.omega[i][2] = -4.0 * atom.x[i][1];
        }

        const long bondsAtStart = sumOverRanks(MPI_COMM_WORLD, static_cast<long>(bonds.localLinks().size()));
        long ownedByLastRankAtEnd = 0;
        for (int chunk = 0; chunk < 20; ++chunk)
        {
            lmp.command(chunk == 0 ? "run 1000" : "run 1000 pre no post no");
            if (resync)
            {
                bonds.table();
                bonds.createBonds(particles, {});
            }
            const long n = sumOverRanks(MPI_COMM_WORLD, static_cast<long>(bonds.localLinks().size()));
            if (n != bondsAtStart || !bonds.failure().empty())
            {
                std::cerr << "rank " << rank << ": " << n << " bonds instead of " << bondsAtStart
                          << " " << bonds.failure() << std::endl;
                status = 1;
                break;
            }
        }
        ownedByLastRankAtEnd = (rank == ranks - 1) ? atom.nlocal : 0;
        MPI_Bcast(&ownedByLastRankAtEnd, 1, MPI_LONG, ranks - 1, MPI_COMM_WORLD);

        // Particle states and, from each bond's lower-tag atom, its history.
        std::vector<double> data;
        for (int i = 0; i < atom.nlocal; ++i)
        {
            data.push_back(0.0);
            data.push_back(atom.tag[i]);
            for (double** a : {atom.x, atom.v, atom.omega})
                data.insert(data.end(), a[i], a[i] + 3);
            for (int slot = 0; slot < bonds.bondCount(i); ++slot)
            {
                const BondState s = bonds.table().read(i, slot, atom.tag[i]);
                if (s.tagA != atom.tag[i]) continue;
                data.insert(data.end(), {1.0, double(s.tagA * 100000 + s.tagB),
                    s.shearDisplacement.x(), s.shearDisplacement.y(), s.shearDisplacement.z(),
                    s.twistAngle, s.bendingAngle.x(), s.bendingAngle.y(), s.bendingAngle.z(),
                    s.restLength});
            }
        }
        // Rows have 11 (particle) or 10 (bond) values: pad particles' to 11, bonds' to 11.
        const std::vector<double> all = gatherDoubles(MPI_COMM_WORLD, data);
        if (rank == 0)
        {
            std::map<std::pair<int, long>, std::vector<double>> rows;
            for (std::size_t k = 0; k < all.size();)
            {
                const int kind = static_cast<int>(all[k]);
                const std::size_t width = kind == 0 ? 11 : 10;
                rows[{kind, static_cast<long>(all[k + 1])}] =
                    std::vector<double>(all.begin() + k + 2, all.begin() + k + width);
                k += width;
            }
            std::ofstream out(argv[1]);
            out << std::setprecision(17);
            out << "# ranks " << ranks << " bonds " << bondsAtStart
                << " atomsOnLastRank " << ownedByLastRankAtEnd << "\n";
            for (const auto& [key, values] : rows)
            {
                out << (key.first == 0 ? "particle " : "bond ") << key.second;
                for (double v : values) out << " " << v;
                out << "\n";
            }
            std::cout << "bondMigration: " << ranks << " rank(s), " << bondsAtStart
                      << " bonds kept, " << ownedByLastRankAtEnd << " atoms on the last rank at the end"
                      << std::endl;
        }
    }
    MPI_Finalize();
    return status;
}
