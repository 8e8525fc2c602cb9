#include "FreezeBondStrength.H"

#include "Dictionary.H"
#include "InputError.H"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace iceDEM
{

double AreaCorrection::newIceFraction(double heatCapacity, double temperatureDrop, double latentHeat)
{
    return heatCapacity*temperatureDrop/latentHeat;
}


double AreaCorrection::iceGrowth(double fraction, double blockVolume, double blockSurface)
{
    return fraction*blockVolume/blockSurface;
}


double AreaCorrection::fromBand
(
    double bandWidth,
    double contactLength,
    int bondsPerContact,
    double bondRadius
)
{
    return bandWidth*contactLength/(bondsPerContact*M_PI*bondRadius*bondRadius);
}


FreezeBondStrengthModel FreezeBondStrengthModel::read(const std::string& path)
{
    return fromDictionary(Dictionary::readFile(path));
}


namespace
{

//- Linear interpolation in log(t) of a table; t must lie inside it.
double interpolateInLogTime
(
    const std::vector<double>& times,
    const std::vector<double>& values,
    double t
)
{
    if (times.size() == 1)
    {
        return values.front();
    }
    std::size_t k = 1;
    while (k + 1 < times.size() && times[k] < t)
    {
        ++k;
    }
    const double w = (std::log(t) - std::log(times[k - 1]))/(std::log(times[k]) - std::log(times[k - 1]));
    return values[k - 1] + w*(values[k] - values[k - 1]);
}

} // namespace


FreezeBondStrengthModel FreezeBondStrengthModel::fromDictionary(const Dictionary& d)
{
    d.checkKeys({"submersionTime", "strengthModel", "confinementLineCoeffs", "fixedSetCoeffs", "areaCorrection"});
    FreezeBondStrengthModel m;
    m.fileName_ = d.fileName();
    const double submersionTime = d.getScalar("submersionTime");
    const std::string kind = d.getChoice("strengthModel", {"confinementLine", "fixedSet"});
    if (kind == "confinementLine")
    {
        m.kind_ = Kind::confinementLine;
        const Dictionary& c = d.subDict("confinementLineCoeffs");
        c.checkKeys({"submersionTimes", "slopes", "intercepts", "shearToTensileRatios"});
        const std::vector<double> times = c.getScalarList("submersionTimes");
        if (times.empty())
        {
            c.fail("submersionTimes", "needs at least one time (minutes)");
        }
        for (std::size_t k = 0; k < times.size(); ++k)
        {
            if (!(times[k] > 0.0) || (k > 0 && !(times[k] > times[k - 1])))
            {
                c.fail("submersionTimes", "must be positive and increasing");
            }
        }
        auto column = [&](const std::string& key, bool nonNegative)
        {
            const std::vector<double> v = c.getScalarList(key);
            if (v.size() != times.size())
            {
                c.fail(key, "needs one value per submersion time (" + std::to_string(times.size()) + ")");
            }
            for (double x : v)
            {
                if (nonNegative && x < 0.0)
                {
                    c.fail(key, "values must not be negative");
                }
            }
            return v;
        };
        const std::vector<double> slopes = column("slopes", true);
        const std::vector<double> intercepts = column("intercepts", false);
        const std::vector<double> ratios = column("shearToTensileRatios", true);
        m.times_ = times;
        m.slopes_ = slopes;
        m.intercepts_ = intercepts;
        m.ratios_ = ratios;
    }
    else
    {
        m.kind_ = Kind::fixedSet;
        const Dictionary& c = d.subDict("fixedSetCoeffs");
        c.checkKeys({"set", "sets"});
        const Dictionary& sets = c.subDict("sets");
        m.setName_ = c.getWord("set");
        if (!sets.isDict(m.setName_))
        {
            std::string allowed;
            for (const std::string& k : sets.keys()) allowed += " " + k;
            c.fail("set", "unknown set '" + m.setName_ + "'; defined in sets:" + allowed);
        }
        const Dictionary& s = sets.subDict(m.setName_);
        s.checkKeys({"tensile", "shear"});
        m.setTensile_ = s.getScalar("tensile");
        m.setShear_ = s.getScalar("shear");
        if (!(m.setTensile_ > 0.0)) s.fail("tensile", "must be positive (Pa)");
        if (!(m.setShear_ > 0.0)) s.fail("shear", "must be positive (Pa)");
        m.shearRatio_ = m.setShear_/m.setTensile_;
    }

    m.setSubmersionTime(submersionTime);

    const Dictionary& a = d.subDict("areaCorrection");
    const std::string areaModel = a.getChoice("model", {"given", "heatBalance", "interface"});
    if (areaModel == "given")
    {
        a.checkKeys({"model", "value"});
        m.areaKind_ = AreaCorrectionKind::given;
        m.areaCorrection_ = a.getScalar("value");
        if (!(m.areaCorrection_ > 0.0))
        {
            a.fail("value", "c_f must be positive");
        }
    }
    else if (areaModel == "heatBalance")
    {
        a.checkKeys({"model", "heatCapacity", "temperatureDrop", "latentHeat", "contactLength",
                     "bandWidthPerGrowth", "bondsPerContact"});
        m.areaKind_ = AreaCorrectionKind::heatBalance;
        auto positive = [&](const std::string& key, double def)
        {
            const double v = a.getScalarOrDefault(key, def);
            if (!(v > 0.0)) a.fail(key, "must be positive");
            return v;
        };
        m.heatCapacity_ = positive("heatCapacity", m.heatCapacity_);
        m.temperatureDrop_ = positive("temperatureDrop", m.temperatureDrop_);
        m.latentHeat_ = positive("latentHeat", m.latentHeat_);
        m.contactLength_ = positive("contactLength", m.contactLength_);
        m.bandWidthPerGrowth_ = positive("bandWidthPerGrowth", m.bandWidthPerGrowth_);
        m.bondsPerContact_ = a.getLabelOrDefault("bondsPerContact", m.bondsPerContact_);
        if (m.bondsPerContact_ < 1) a.fail("bondsPerContact", "must be at least 1");
    }
    else
    {
        a.checkKeys({"model"});
        m.areaKind_ = AreaCorrectionKind::interface;
    }
    return m;
}


void FreezeBondStrengthModel::setSubmersionTime(double t)
{
    if (!(t > 0.0))
    {
        throw InputError(fileName_, "submersionTime", "must be positive (minutes)");
    }
    submersionTime_ = t;
    if (kind_ == Kind::fixedSet)
    {
        return;
    }
    if (t < times_.front()*(1 - 1e-12) || t > times_.back()*(1 + 1e-12))
    {
        std::ostringstream msg;
        msg << "submersion time " << t << " min lies outside the table ("
            << times_.front() << " to " << times_.back() << " min of confinementLineCoeffs.submersionTimes)";
        throw InputError(fileName_, "submersionTime", msg.str());
    }
    slope_ = interpolateInLogTime(times_, slopes_, t);
    intercept_ = interpolateInLogTime(times_, intercepts_, t);
    shearRatio_ = interpolateInLogTime(times_, ratios_, t);
}


void FreezeBondStrengthModel::setSetStrengths(double tensile, double shear)
{
    if (kind_ != Kind::fixedSet)
    {
        throw InputError(fileName_, "strengthModel", "must be fixedSet to override the set's strengths");
    }
    if (!(tensile > 0.0 && shear > 0.0))
    {
        throw std::invalid_argument("FreezeBondStrengthModel::setSetStrengths: strengths must be positive");
    }
    setTensile_ = tensile;
    setShear_ = shear;
    shearRatio_ = shear/tensile;
}


void FreezeBondStrengthModel::setAreaCorrection(double cf)
{
    if (!(cf > 0.0) || !std::isfinite(cf))
    {
        throw std::invalid_argument("FreezeBondStrengthModel::setAreaCorrection: c_f must be positive");
    }
    areaCorrection_ = cf;
}


double FreezeBondStrengthModel::heatBalanceAreaCorrection
(
    double blockVolume,
    double blockSurface,
    double bondRadius
) const
{
    const double fraction = AreaCorrection::newIceFraction(heatCapacity_, temperatureDrop_, latentHeat_);
    const double growth = AreaCorrection::iceGrowth(fraction, blockVolume, blockSurface);
    return AreaCorrection::fromBand(bandWidthPerGrowth_*growth, contactLength_, bondsPerContact_, bondRadius);
}


double FreezeBondStrengthModel::tensileAt(double pressure) const
{
    if (kind_ == Kind::fixedSet)
    {
        return setTensile_;
    }
    return std::max(0.0, slope_*std::max(0.0, pressure) + intercept_);
}


FreezeBondStrength FreezeBondStrengthModel::strength(double contactForce, double bondArea) const
{
    FreezeBondStrength s;
    s.confinement = std::max(0.0, contactForce)/(areaCorrection_*bondArea);
    const double realTensile = tensileAt(s.confinement);
    const double realShear = kind_ == Kind::fixedSet ? setShear_ : shearRatio_*realTensile;
    s.tensile = areaCorrection_*realTensile;
    s.shear = areaCorrection_*realShear;
    return s;
}


std::string FreezeBondStrengthModel::summary() const
{
    std::ostringstream out;
    if (kind_ == Kind::confinementLine)
    {
        out << "freeze-bonds after " << submersionTime_ << " min: sigma_T = " << slope_ << " p_c + " << intercept_*1e-3 << " kPa, shear/tensile " << shearRatio_;
    }
    else
    {
        out << "freeze-bond set " << setName_ << ": tensile " << setTensile_*1e-3 << " kPa, shear " << setShear_*1e-3 << " kPa";
    }
    out << "; area correction c_f = " << areaCorrection_;
    return out.str();
}

} // namespace iceDEM
