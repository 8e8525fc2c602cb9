#include "SceneSetup.H"

#include "AtomicFile.H"
#include "LiggghtsInstance.H"

#include <algorithm>
#include <iomanip>
#include <mpi.h>
#include <sstream>

namespace iceDEM
{

void writeLiggghtsData
(
    const std::string& path,
    const std::string& title,
    const std::vector<ParticleSpec>& particles,
    double density,
    const Vec3& lo,
    const Vec3& hi,
    int atomTypes,
    const std::function<int(const ParticleSpec&)>& typeOf
)
{
    writeStreamAtomically(path, [&](std::ostream& out)
    {
        out << "LIGGGHTS data file: " << title << "\n\n"
            << particles.size() << " atoms\n" << atomTypes << " atom types\n\n"
            << std::setprecision(17)
            << lo.x() << " " << hi.x() << " xlo xhi\n"
            << lo.y() << " " << hi.y() << " ylo yhi\n"
            << lo.z() << " " << hi.z() << " zlo zhi\n\nAtoms\n\n";
        for (std::size_t k = 0; k < particles.size(); ++k)
        {
            const ParticleSpec& p = particles[k];
            out << k + 1 << " " << typeOf(p) << " " << 2.0*p.radius << " " << density << " "
                << p.position.x() << " " << p.position.y() << " " << p.position.z() << "\n";
        }
    });
}


void defineScriptVariables
(
    LiggghtsInstance& lmp,
    const ScriptVariables& variables,
    const std::string& generatedPath,
    const std::string& writtenBy
)
{
    std::ostringstream script;
    script << "# written by " << writtenBy << "\n";
    for (const auto& [name, value] : variables)
    {
        lmp.setVariable(name, value);
        script << "variable " << name << " index " << value << "\n";
    }
    int rank = 0;
    MPI_Comm_rank(lmp.communicator(), &rank);
    if (rank == 0)
    {
        writeFileAtomically(generatedPath, script.str());
    }
}


ScriptVariables contactVariables(const ContactParameters& c)
{
    return
    {
        {"kn", exactNumber(c.normalStiffness)},
        {"kt", exactNumber(c.tangentialStiffness)},
        {"gn", exactNumber(c.normalDamping)},
        {"gt", exactNumber(c.tangentialDamping)},
        {"mu", exactNumber(c.friction)},
        {"muR", exactNumber(c.rollingFriction)}
    };
}


double bondGhostCutoff(const IceProperties& ice, double maxRadius, double skin)
{
    const double maxDistFactor =
        std::max(ice.family(BondFamily::ice).distFactor, ice.family(BondFamily::freeze).distFactor);
    return 1.1*maxDistFactor*2.0*maxRadius + skin;
}

std::string typePairMatrix(double ice, double wall)
{
    constexpr int wallType = 3;
    std::ostringstream m;
    m << std::setprecision(17);
    for (int a = 1; a <= 3; ++a)
        for (int b = 1; b <= 3; ++b)
            m << (a == wallType || b == wallType ? wall : ice) << (a == 3 && b == 3 ? "" : " ");
    return m.str();
}

ScriptVariables boxContactVariables(const ContactParameters& c)
{
    auto matrix = [](double ice, double wall) { return "\"" + typePairMatrix(ice, wall) + "\""; };
    return
    {
        {"knMatrix", matrix(c.normalStiffness, c.normalStiffness)},
        {"ktMatrix", matrix(c.tangentialStiffness, c.tangentialStiffness)},
        {"gnMatrix", matrix(c.normalDamping, c.normalDamping)},
        {"gtMatrix", matrix(c.tangentialDamping, c.tangentialDamping)},
        {"muMatrix", matrix(c.friction, 0.0)},
        {"muRMatrix", matrix(c.rollingFriction, 0.0)}
    };
}

} // namespace iceDEM
