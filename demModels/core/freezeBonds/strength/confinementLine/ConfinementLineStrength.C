#include "ConfinementLineStrength.H"

#include "Dictionary.H"
#include "InputError.H"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace iceDEM
{

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


ConfinementLineStrength::ConfinementLineStrength(const Dictionary& d)
:
    FreezeBondStrengthModel(d.fileName())
{
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
    slopes_ = column("slopes", true);
    intercepts_ = column("intercepts", false);
    ratios_ = column("shearToTensileRatios", true);
    times_ = times;
}


void ConfinementLineStrength::atSubmersionTime(double t)
{
    if (t < times_.front()*(1 - 1e-12) || t > times_.back()*(1 + 1e-12))
    {
        std::ostringstream msg;
        msg << "submersion time " << t << " min lies outside the table ("
            << times_.front() << " to " << times_.back() << " min of confinementLineCoeffs.submersionTimes)";
        throw InputError(fileName(), "submersionTime", msg.str());
    }
    slope_ = interpolateInLogTime(times_, slopes_, t);
    intercept_ = interpolateInLogTime(times_, intercepts_, t);
    shearRatio_ = interpolateInLogTime(times_, ratios_, t);
}


double ConfinementLineStrength::tensile(double pressure) const
{
    return std::max(0.0, slope_*std::max(0.0, pressure) + intercept_);
}


double ConfinementLineStrength::shear(double realTensile) const
{
    return shearRatio_*realTensile;
}


std::string ConfinementLineStrength::summary() const
{
    std::ostringstream out;
    out << "freeze-bonds after " << submersionTime() << " min: sigma_T = " << slope_ << " p_c + "
        << intercept_*1e-3 << " kPa, shear/tensile " << shearRatio_;
    return out.str();
}

} // namespace iceDEM
