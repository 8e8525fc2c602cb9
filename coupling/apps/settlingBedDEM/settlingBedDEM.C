// settlingBedDEM: the DEM script of an iceFoam case run without the CFD, with
// water level `none` (no water) or `hydrostatic` (still water with a flat
// surface at waterLevel: buoyancy and Schiller-Naumann drag, WaterForces), so
// that one scene can be timed at all three levels (cases/settlingBed).
//
// Usage: settlingBedDEM -hydrodynamics none|hydrostatic [-case DIR] [-endTime T]
// Reads  constant/couplingProperties (demScript, demVariables, waterLevel,
//        addedMassCoefficient), constant/transportProperties (rho, nu),
//        system/controlDict (endTime, unless -endTime). The script gets the
//        variable cfd = 0 (iceFoam passes 1), so that it leaves out its
//        `fix external` for the fluid.
// Writes postProcessing/settlingBedDEM_<level>.json (wall time, steps,
//        particles, mean and top particle height), progress on stdout.

#include "AppMain.H"
#include "CommandLine.H"
#include "AtomicFile.H"
#include "Dictionary.H"
#include "HydrostaticWater.H"
#include "InputError.H"
#include "Json.H"
#include "LiggghtsInstance.H"
#include "ParticleGather.H"
#include "WaterForces.H"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <vector>
#include <string>

using namespace iceDEM;

namespace
{

struct Options
{
    std::string caseDir = ".";
    std::string level;
    double endTime = 0.0;   // 0: controlDict's
};

Options readOptions(int argc, char** argv)
{
    Options o;
    CommandLine("settlingBedDEM")
        .choice("-hydrodynamics", {"none", "hydrostatic"}, "the water level (cfd is iceFoam's); required", o.level)
        .text("-case", "DIR", "the case directory (default .)", o.caseDir)
        .positive("-endTime", "S", "end time instead of system/controlDict's", o.endTime)
        .parse(argc, argv);
    if (o.level.empty())
    {
        throw InputError("command line", "-hydrodynamics", "must be given: none or hydrostatic; level cfd is iceFoam's");
    }
    return o;
}

std::string tokensText(const Dictionary::Entry& e)
{
    std::string text;
    for (const DictToken& t : e.tokens)
    {
        text += (text.empty() ? "" : " ") + t.text;
    }
    return text;
}

void run(MPI_Comm comm, const Options& o)
{
    namespace fs = std::filesystem;
    const fs::path dir(o.caseDir);
    const Dictionary props = Dictionary::readFile((dir / "constant" / "couplingProperties").string());
    const Dictionary transport = Dictionary::readFile((dir / "constant" / "transportProperties").string());
    const Dictionary control = Dictionary::readFile((dir / "system" / "controlDict").string());
    const double endTime = o.endTime > 0 ? o.endTime : control.getPositiveScalarOrDefault("endTime", 1.0);

    int rank = 0;
    MPI_Comm_rank(comm, &rank);
    LiggghtsInstance lmp(comm, (dir / "DEM" / ("log.liggghts." + o.level)).string());
    const Dictionary& vars = props.subDict("demVariables");
    for (const std::string& key : vars.keys())
    {
        lmp.setVariable(key, tokensText(vars.entry(key)));
    }
    lmp.setVariable("cfd", "0");
    lmp.runScript((dir / props.getString("demScript")).string());

    std::unique_ptr<WaterForces> water;
    if (o.level == "hydrostatic")
    {
        HydrostaticWaterParameters w;
        w.surfaceLevel = props.getScalar("waterLevel");
        w.density = transport.getPositiveScalarOrDefault("rho", 1000.0);
        w.viscosity = w.density*transport.getPositiveScalarOrDefault("nu", 1.79e-6);
        w.addedMassCoefficient = props.getScalarOrDefault("addedMassCoefficient", 0.0);
        water = std::make_unique<WaterForces>(lmp, HydrostaticWater(w));
        water->defineForceFix();
        water->defineAddedMassFix();
    }

    const long steps = std::lround((endTime - lmp.time())/lmp.timeStep());
    const long chunk = std::max(1L, steps/20);
    const auto start = std::chrono::steady_clock::now();
    for (long done = 0; done < steps;)
    {
        const long n = std::min(chunk, steps - done);
        lmp.command("run " + std::to_string(n) + (done == 0 ? " post no" : " pre no post no"));
        done += n;
        const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        if (rank == 0)
        {
            std::cout << "t = " << lmp.time() << " s (" << done << "/" << steps << " steps), wall " << wall
                      << " s, about " << wall*(steps - done)/done << " s left" << std::endl;
        }
    }
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

    const std::vector<Vec3> particles = allPositionsByTag(lmp);
    double meanZ = 0.0, topZ = -1e30;
    for (const Vec3& x : particles)
    {
        meanZ += x.z();
        topZ = std::max(topZ, x.z());
    }
    meanZ /= std::max<std::size_t>(1, particles.size());
    if (rank == 0)
    {
        Json json;
        json["hydrodynamics"] = o.level;
        json["particles"] = static_cast<long>(particles.size());
        json["steps"] = steps;
        json["dt"] = lmp.timeStep();
        json["simulated_s"] = steps*lmp.timeStep();
        json["wall_s"] = wall;
        json["wall_s_per_simulated_s"] = wall/(steps*lmp.timeStep());
        json["mean_height_m"] = meanZ;
        json["top_height_m"] = topZ;
        fs::create_directories(dir / "postProcessing");
        writeFileAtomically((dir / "postProcessing" / ("settlingBedDEM_" + o.level + ".json")).string(),
                            jsonText(json));
        std::cout << "settlingBedDEM " << o.level << ": " << particles.size() << " particles, " << steps
                  << " steps in " << wall << " s wall clock; mean height " << meanZ << " m" << std::endl;
    }
}

} // namespace

int main(int argc, char** argv)
{
    return runApplication(argc, argv, "settlingBedDEM", [&](MPI_Comm comm) { run(comm, readOptions(argc, argv)); });
}
