#include "WaterProperties.H"

#include "Dictionary.H"
#include "InputError.H"

#include <cmath>
#include <filesystem>
#include <sstream>

namespace iceDEM
{

std::string toString(WaterLevel level)
{
    return waterLevelNames.nameOr(level, "?");
}


namespace
{

double positiveScalar(const Dictionary& d, const std::string& key, const std::string& unit)
{
    if (!d.found(key)) d.fail(key, "missing; expected a positive number in " + unit);
    const double x = d.getScalar(key);
    if (!(x > 0.0))
    {
        std::ostringstream s;
        s << x << " is not allowed; expected a positive number in " << unit;
        d.fail(key, s.str());
    }
    return x;
}


HydrostaticWaterParameters readHydrostatic(const Dictionary& d)
{
    d.checkKeys({"surfaceLevel", "rho", "mu", "addedMassCoefficient", "drag"});

    HydrostaticWaterParameters p;
    if (!d.found("surfaceLevel"))
    {
        d.fail("surfaceLevel", "missing; expected the z of the water surface in m, or floating");
    }
    if (d.getString("surfaceLevel") == "floating")
    {
        p.floatingSurface = true;
    }
    else
    {
        p.surfaceLevel = d.getScalar("surfaceLevel");
    }
    p.density = positiveScalar(d, "rho", "kg/m3");
    p.viscosity = positiveScalar(d, "mu", "Pa s");
    p.addedMassCoefficient = d.getScalarOrDefault("addedMassCoefficient", 0.5);
    if (p.addedMassCoefficient < 0.0)
    {
        std::ostringstream s;
        s << p.addedMassCoefficient << " is not allowed; expected a number >= 0 (0.5 for a sphere, 0: off)";
        d.fail("addedMassCoefficient", s.str());
    }
    p.drag =
        hydrostaticDragNames.getOrDefault(d, "drag", HydrostaticDrag::SchillerNaumann)
     == HydrostaticDrag::SchillerNaumann;
    return p;
}


Vec3 readGravity(const std::string& file)
{
    const Dictionary d = Dictionary::readFile(file);
    d.checkKeys({"dimensions", "value"});
    const std::vector<double> g = d.getScalarList("value");
    if (g.size() != 3)
    {
        d.fail("value", "expected a vector of 3 numbers, e.g. (0 0 -9.81)");
    }
    if (g[0] != 0.0 || g[1] != 0.0 || !(g[2] < 0.0))
    {
        d.fail("value", "gravity must point along -z, e.g. (0 0 -9.81): the water surface is a plane z = const");
    }
    return Vec3(g[0], g[1], g[2]);
}

} // namespace


WaterProperties WaterProperties::read
(
    const std::string& couplingFile,
    const std::string& gravityFile,
    bool floatingSurfaceAllowed
)
{
    const Dictionary dict = Dictionary::readFile(couplingFile);
    WaterProperties w;
    w.level = waterLevelNames.get(dict, "waterLevel");

    if (w.level == WaterLevel::hydrostatic || dict.found("hydrostatic"))
    {
        if (!dict.isDict("hydrostatic"))
        {
            dict.fail("hydrostatic", "missing; waterLevel hydrostatic needs a sub-dictionary"
                      " hydrostatic { surfaceLevel; rho; mu; }");
        }
        const Dictionary& hydrostatic = dict.subDict("hydrostatic");
        w.hydrostatic = readHydrostatic(hydrostatic);
        if (w.hydrostatic.floatingSurface && !floatingSurfaceAllowed)
        {
            hydrostatic.fail("surfaceLevel", "floating is only for scenes that assemble floating ice "
                "(ridgeDEM); expected the z of the water surface in m");
        }
    }
    if (!gravityFile.empty())
    {
        w.gravity = readGravity(gravityFile);
    }
    else if (w.level == WaterLevel::hydrostatic)
    {
        throw InputError(couplingFile, "waterLevel",
            "hydrostatic water needs gravity: add constant/g with `value (0 0 -9.81);`");
    }
    w.hydrostatic.gravity = -w.gravity.z();
    return w;
}


WaterProperties WaterProperties::readCase(const std::string& caseDir, bool floatingSurfaceAllowed)
{
    const std::string g = caseDir + "/constant/g";
    return read(caseDir + "/constant/couplingProperties", std::filesystem::exists(g) ? g : "", floatingSurfaceAllowed);
}

} // namespace iceDEM
