#include "IceProperties.H"
#include "Dictionary.H"

#include <limits>
#include <sstream>

namespace iceDEM
{

namespace
{

constexpr double inf = std::numeric_limits<double>::infinity();

//- Allowed interval of a scalar entry and how to describe it to the user.
struct Bound
{
    double lo;
    bool loIncluded;
    double hi;
    bool hiIncluded;
    std::string description;

    bool contains(double x) const
    {
        return (loIncluded ? x >= lo : x > lo) && (hiIncluded ? x <= hi : x < hi);
    }
};

Bound positive(const std::string& unit = "")
{
    return {0, false, inf, false, "a positive number" + (unit.empty() ? "" : " in " + unit)};
}

Bound nonNegative()
{
    return {0, true, inf, false, "a number >= 0"};
}

Bound halfOpen(double lo, double hi)
{
    std::ostringstream s;
    s << "a number in [" << lo << ", " << hi << ")";
    return {lo, true, hi, false, s.str()};
}

double readScalar(const Dictionary& d, const std::string& key, const Bound& b)
{
    if (!d.found(key)) d.fail(key, "missing; expected " + b.description);
    const double x = d.getScalar(key);
    if (!b.contains(x))
    {
        std::ostringstream s;
        s << x << " is out of range; expected " << b.description;
        d.fail(key, s.str());
    }
    return x;
}

double readScalarOrDefault(const Dictionary& d, const std::string& key, const Bound& b, double def)
{
    return d.found(key) ? readScalar(d, key, b) : def;
}


MaterialProperties readMaterial(const Dictionary& d)
{
    d.checkKeys
    ({
        "density", "youngsModulus", "poissonsRatio",
        "frictionCoefficient", "rollingFrictionCoefficient"
    });

    MaterialProperties m;
    m.density = readScalar(d, "density", positive("kg/m3"));
    m.youngsModulus = readScalar(d, "youngsModulus", positive("Pa"));
    m.poissonsRatio = readScalar(d, "poissonsRatio", halfOpen(0, 0.5));
    m.frictionCoefficient = readScalar(d, "frictionCoefficient", nonNegative());
    m.rollingFrictionCoefficient = readScalar(d, "rollingFrictionCoefficient", nonNegative());
    return m;
}


BondFamilyParameters readFamily(const Dictionary& d)
{
    d.checkKeys
    ({
        "distFactor", "youngsModulus", "compressionModulus", "poissonsRatio", "radiusMultiplier",
        "strengthModel", "breakN", "beta", "tensileStrength", "shearStrength",
        "twistStrengthFactor", "bendingStrengthFactor", "breakageCriterion", "unbreakable"
    });

    BondFamilyParameters f;
    f.distFactor = readScalar(d, "distFactor", {1, true, inf, false, "a number >= 1"});
    f.youngsModulus = readScalar(d, "youngsModulus", positive("Pa"));
    f.compressionModulus = readScalarOrDefault(d, "compressionModulus", positive("Pa"), 0.0);   // 0: youngsModulus
    f.poissonsRatio = readScalar(d, "poissonsRatio", halfOpen(0, 0.5));
    f.radiusMultiplier = readScalar(d, "radiusMultiplier", positive());

    f.strengthModel = strengthModelNames.get(d, "strengthModel");

    // Only the chosen model's entries are required; the other model's are
    // checked when given, so that switching models is a one-word edit.
    const bool strain = f.strengthModel == StrengthModel::strain;
    auto strength = [&](const std::string& key, const Bound& b, bool required, double def)
    {
        return required ? readScalar(d, key, b) : readScalarOrDefault(d, key, b, def);
    };
    f.breakN = strength("breakN", positive(), strain, f.breakN);
    f.beta = strength("beta", positive(), strain, f.beta);
    const bool stress = f.strengthModel == StrengthModel::stress;
    f.tensileStrength = strength("tensileStrength", positive("Pa"), stress, f.tensileStrength);
    f.shearStrength = strength("shearStrength", positive("Pa"), stress, f.shearStrength);

    f.twistStrengthFactor = readScalarOrDefault(d, "twistStrengthFactor", positive(), 1.0);
    f.bendingStrengthFactor = readScalarOrDefault(d, "bendingStrengthFactor", positive(), 1.0);
    f.criterion = breakageCriterionNames.getOrDefault(d, "breakageCriterion", BreakageCriterion::separate);
    f.unbreakable = d.getBoolOrDefault("unbreakable", false);
    return f;
}


DampingParameters readDamping(const Dictionary& d)
{
    d.checkKeys({"model", "hystereticCoeffs", "viscousCoeffs"});

    DampingParameters p;
    p.model = dampingModelNames.get(d, "model");

    // The coefficients of the chosen model are required, the others checked when given.
    if (p.model == DampingModel::hysteretic || d.found("hystereticCoeffs"))
    {
        const Dictionary& c = d.subDict("hystereticCoeffs");
        c.checkKeys({"alpha"});
        p.alpha = readScalar(c, "alpha", halfOpen(0, 1));
    }
    if (p.model == DampingModel::viscous || d.found("viscousCoeffs"))
    {
        const Dictionary& c = d.subDict("viscousCoeffs");
        c.checkKeys({"dampingRatio"});
        p.dampingRatio = readScalar(c, "dampingRatio", nonNegative());
    }
    return p;
}


TimeStepParameters readTimeStep(const Dictionary& d)
{
    d.checkKeys({"factor", "deltaT", "refuseUnsafe"});

    TimeStepParameters t;
    t.factor = readScalarOrDefault(d, "factor", positive(), t.factor);
    t.deltaT = readScalarOrDefault
    (
        d, "deltaT",
        {0, true, inf, false, "a number >= 0 in s (0: use timeStep.factor)"},
        t.deltaT
    );
    t.refuseUnsafe = d.getBoolOrDefault("refuseUnsafe", t.refuseUnsafe);
    return t;
}

} // namespace


IceProperties IceProperties::read(const std::string& path)
{
    const Dictionary dict = Dictionary::readFile(path);
    dict.checkKeys({"material", "bondFamilies", "damping", "timeStep", "maxBondsPerParticle"});

    IceProperties props;
    props.material = readMaterial(dict.subDict("material"));

    const Dictionary& families = dict.subDict("bondFamilies");
    families.checkKeys(bondFamilyNames.names());
    const BondFamilyParameters ice = readFamily(families.subDict(toString(BondFamily::ice)));
    props.families[static_cast<int>(BondFamily::ice)] = ice;
    props.families[static_cast<int>(BondFamily::freeze)] =
        families.found(toString(BondFamily::freeze))
      ? readFamily(families.subDict(toString(BondFamily::freeze)))
      : ice;

    props.damping = readDamping(dict.subDict("damping"));

    if (dict.found("timeStep"))
    {
        props.timeStep = readTimeStep(dict.subDict("timeStep"));
    }

    props.maxBondsPerParticle = dict.getLabelOrDefault("maxBondsPerParticle", 16);
    if (props.maxBondsPerParticle < 1 || props.maxBondsPerParticle > 64)
    {
        dict.fail
        (
            "maxBondsPerParticle",
            std::to_string(props.maxBondsPerParticle)
          + " is out of range; expected an integer in [1, 64]"
        );
    }
    return props;
}

IceProperties IceProperties::softenedForAssembly(double youngsModulus, double dampingAlpha) const
{
    IceProperties soft = *this;
    soft.material.youngsModulus = youngsModulus;
    for (BondFamilyParameters& f : soft.families)
    {
        f.youngsModulus = youngsModulus;
        f.compressionModulus = 0.0;
        f.unbreakable = true;
    }
    soft.damping.model = DampingModel::hysteretic;
    soft.damping.alpha = dampingAlpha;
    return soft;
}

} // namespace iceDEM
