#include "ForceCurveAnalysis.H"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace iceDEM
{

namespace
{

constexpr double notANumber = std::numeric_limits<double>::quiet_NaN();

void checkCurve(const std::vector<double>& displacement, const std::vector<double>& force)
{
    if (displacement.size() != force.size())
    {
        throw std::invalid_argument
        (
            "force curve: " + std::to_string(displacement.size()) + " displacements but "
          + std::to_string(force.size()) + " forces"
        );
    }
    for (std::size_t i = 0; i < force.size(); ++i)
    {
        if (!std::isfinite(displacement[i]) || !std::isfinite(force[i]))
        {
            throw std::invalid_argument
            (
                "force curve: non-finite value at sample " + std::to_string(i)
            );
        }
    }
}

void checkOptions(const ForceCurveOptions& o)
{
    if (!(o.lowFraction > 0.0 && o.lowFraction < o.highFraction && o.highFraction <= 1.0))
    {
        throw std::invalid_argument("force curve: need 0 < lowFraction < highFraction <= 1");
    }
    if (!(o.halfFraction > 0.0 && o.halfFraction < 1.0))
    {
        throw std::invalid_argument("force curve: need 0 < halfFraction < 1");
    }
}

// Displacement where the line through samples i-1 and i reaches level.
double crossing
(
    const std::vector<double>& displacement,
    const std::vector<double>& force,
    std::size_t i,
    double level
)
{
    const double f0 = force[i - 1];
    const double f1 = force[i];
    const double d0 = displacement[i - 1];
    const double d1 = displacement[i];
    if (f1 == f0)
    {
        return d1;
    }
    return d0 + (level - f0)*(d1 - d0)/(f1 - f0);
}

struct LineFit
{
    double slope = notANumber;
    double r2 = notANumber;
};

LineFit fitLine
(
    const std::vector<double>& x,
    const std::vector<double>& y,
    std::size_t begin,
    std::size_t end
)
{
    LineFit fit;
    const std::size_t n = end - begin;
    if (n < 2)
    {
        return fit;
    }
    double meanX = 0.0;
    double meanY = 0.0;
    for (std::size_t i = begin; i < end; ++i)
    {
        meanX += x[i];
        meanY += y[i];
    }
    meanX /= n;
    meanY /= n;
    double sxx = 0.0;
    double sxy = 0.0;
    double syy = 0.0;
    for (std::size_t i = begin; i < end; ++i)
    {
        const double dx = x[i] - meanX;
        const double dy = y[i] - meanY;
        sxx += dx*dx;
        sxy += dx*dy;
        syy += dy*dy;
    }
    if (sxx <= 0.0)
    {
        return fit;
    }
    fit.slope = sxy/sxx;
    // Residual sum of squares of the least-squares line: syy - slope*sxy.
    fit.r2 = syy > 0.0 ? 1.0 - std::max(0.0, syy - fit.slope*sxy)/syy : 1.0;
    return fit;
}

} // namespace


ForceCurveResult analyseForceCurve
(
    const std::vector<double>& displacement,
    const std::vector<double>& force,
    const ForceCurveOptions& options
)
{
    checkCurve(displacement, force);
    checkOptions(options);
    if (force.size() < 2)
    {
        throw std::invalid_argument("force curve: fewer than two samples");
    }

    ForceCurveResult result;
    result.peakIndex =
        static_cast<std::size_t>(std::max_element(force.begin(), force.end()) - force.begin());
    result.peakForce = force[result.peakIndex];
    result.travelAtPeak = displacement[result.peakIndex];
    if (!(result.peakForce > 0.0))
    {
        throw std::invalid_argument("force curve: no positive force");
    }

    const double low = options.lowFraction*result.peakForce;
    const double high = options.highFraction*result.peakForce;
    std::size_t begin = 0;
    while (begin < result.peakIndex && force[begin] < low)
    {
        ++begin;
    }
    std::size_t end = begin;
    while (end < result.peakIndex && force[end] <= high)
    {
        ++end;
    }
    const LineFit fit = fitLine(displacement, force, begin, end);
    result.elasticSlope = fit.slope;
    result.slopeFitR2 = fit.r2;
    result.slopeFitPoints = end - begin;

    const double half = options.halfFraction*result.peakForce;
    result.halfLoadTravelAfterPeak = notANumber;
    for (std::size_t i = result.peakIndex + 1; i < force.size(); ++i)
    {
        if (force[i] <= half)
        {
            result.halfLoadTravelAfterPeak =
                crossing(displacement, force, i, half) - result.travelAtPeak;
            result.halfLoadReached = true;
            break;
        }
    }
    return result;
}


FirstPeak firstPeak
(
    const std::vector<double>& displacement,
    const std::vector<double>& force,
    double dropFraction,
    double minFraction
)
{
    if (displacement.size() != force.size() || force.empty())
    {
        throw std::invalid_argument("firstPeak: displacement and force must be non-empty and of equal length");
    }
    const double floor = minFraction * *std::max_element(force.begin(), force.end());
    FirstPeak best;
    bool candidate = false;
    for (std::size_t k = 0; k < force.size(); ++k)
    {
        if (force[k] >= floor && (!candidate || force[k] > best.force))
        {
            best = {force[k], displacement[k], k};
            candidate = true;
        }
        else if (candidate && force[k] <= (1.0 - dropFraction) * best.force)
        {
            return best;
        }
    }
    return best;
}


double contactOnset
(
    const std::vector<double>& displacement,
    const std::vector<double>& force,
    double threshold
)
{
    checkCurve(displacement, force);
    for (std::size_t i = 0; i < force.size(); ++i)
    {
        if (force[i] > threshold)
        {
            return i == 0 ? displacement[0] : crossing(displacement, force, i, threshold);
        }
    }
    return notANumber;
}

namespace
{

double median(std::vector<double> values)
{
    if (values.empty())
    {
        return 0.0;
    }
    const std::size_t n = values.size();
    std::nth_element(values.begin(), values.begin() + n / 2, values.end());
    const double upper = values[n / 2];
    if (n % 2 == 1)
    {
        return upper;
    }
    return 0.5 * (*std::max_element(values.begin(), values.begin() + n / 2) + upper);
}

} // namespace


double kineticToElasticNearPeak
(
    const std::vector<double>& force,
    const std::vector<double>& kinetic,
    const std::vector<double>& elastic,
    double halfFraction
)
{
    if (kinetic.size() != force.size() || elastic.size() != force.size())
    {
        throw std::invalid_argument("kineticToElasticNearPeak: force, kinetic and elastic differ in length");
    }
    if (force.empty())
    {
        return 0.0;
    }
    const std::size_t peak = std::max_element(force.begin(), force.end()) - force.begin();
    std::vector<double> ratios;
    for (std::size_t k = 0; k <= peak; ++k)
    {
        if (force[k] >= halfFraction * force[peak] && elastic[k] > 0.0)
        {
            ratios.push_back(kinetic[k] / elastic[k]);
        }
    }
    return median(ratios);
}

double kineticToWork
(
    const std::vector<double>& travel,
    const std::vector<double>& force,
    const std::vector<double>& kinetic
)
{
    if (force.size() != travel.size() || kinetic.size() != travel.size())
    {
        throw std::invalid_argument("kineticToWork: travel, force and kinetic differ in length");
    }
    std::vector<double> ratios;
    double work = 0.0;
    for (std::size_t k = 1; k < travel.size(); ++k)
    {
        work += 0.5 * (force[k] + force[k - 1]) * (travel[k] - travel[k - 1]);
        if (work > 0.0)
        {
            ratios.push_back(kinetic[k] / work);
        }
    }
    return median(ratios);
}

} // namespace iceDEM
