#include "CalibratedParticleStrength.H"

#include "Dictionary.H"
#include "IceProperties.H"
#include "InputError.H"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace iceDEM
{

namespace
{

std::string kPa(double pascals)
{
    std::ostringstream out;
    out.precision(4);
    out << pascals*1e-3 << " kPa";
    return out.str();
}

//- y(x) on the polyline through (xs, ys), extended along its end segments.
double alongPolyline(const std::vector<double>& xs, const std::vector<double>& ys, double x)
{
    std::size_t k = 1;
    while (k + 1 < xs.size() && xs[k] < x)
    {
        ++k;
    }
    return ys[k - 1] + (ys[k] - ys[k - 1])*(x - xs[k - 1])/(xs[k] - xs[k - 1]);
}

} // namespace


CalibratedParticleStrength::CalibratedParticleStrength(const Dictionary& d)
:
    FreezeBondParticleStrength(d.fileName())
{
    if (!d.isDict("calibratedCoeffs"))
    {
        d.fail("calibratedCoeffs", "particleStrengths calibrated needs the calibratedCoeffs sub-dictionary "
            "(cases/common/freezeBondCalibration)");
    }
    const Dictionary& c = d.subDict("calibratedCoeffs");
    c.checkKeys({"ratios", "shearSlopes", "shearIntercepts", "tensileSlopes", "tensileIntercepts",
                 "particleShears", "effectiveShears", "effectiveTensiles", "confinement",
                 "freezeToIceModulusRatio", "freezeCompressionToIceModulusRatio", "relativeError"});
    ratios_ = c.getScalarList("ratios");
    if (ratios_.empty())
    {
        c.fail("ratios", "needs at least one ratio T_p / S_p");
    }
    for (std::size_t k = 0; k < ratios_.size(); ++k)
    {
        if (!(ratios_[k] > 0.0) || (k > 0 && !(ratios_[k] > ratios_[k - 1])))
        {
            c.fail("ratios", "must be positive and increasing");
        }
    }
    auto column = [&](const std::string& key, bool positive)
    {
        const std::vector<double> v = c.getScalarList(key);
        if (v.size() != ratios_.size())
        {
            c.fail(key, "needs one value per ratio (" + std::to_string(ratios_.size()) + ")");
        }
        for (double x : v)
        {
            if (positive && !(x > 0.0))
            {
                c.fail(key, "values must be positive: the effective strength must rise with the particle one");
            }
        }
        return v;
    };
    points_ = c.found("particleShears");
    if (points_)
    {
        readPoints(c);
    }
    else
    {
        shearSlopes_ = column("shearSlopes", true);
        shearIntercepts_ = column("shearIntercepts", false);
        tensileSlopes_ = column("tensileSlopes", true);
        tensileIntercepts_ = column("tensileIntercepts", false);
    }
    confinement_ = c.getScalar("confinement");
    if (confinement_ < 0.0) c.fail("confinement", "must not be negative (Pa)");
    modulusRatio_ = c.getScalar("freezeToIceModulusRatio");
    if (!(modulusRatio_ > 0.0)) c.fail("freezeToIceModulusRatio", "must be positive");
    // Calibrations made before bonds had a modulus of their own in compression had the same in both.
    compressionRatio_ = c.found("freezeCompressionToIceModulusRatio")
                      ? c.getScalar("freezeCompressionToIceModulusRatio") : modulusRatio_;
    if (!(compressionRatio_ > 0.0)) c.fail("freezeCompressionToIceModulusRatio", "must be positive");
    relativeError_ = c.getScalar("relativeError");
    if (relativeError_ < 0.0) c.fail("relativeError", "must not be negative");
}


void CalibratedParticleStrength::readPoints(const Dictionary& c)
{
    for (const char* key : {"shearSlopes", "shearIntercepts", "tensileSlopes", "tensileIntercepts"})
    {
        if (c.found(key))
        {
            c.fail(key, "the points form (particleShears) and the lines form exclude each other");
        }
    }
    particleShears_ = c.getScalarList("particleShears");
    if (particleShears_.size() < 2)
    {
        c.fail("particleShears", "needs at least two particle shear strengths S_p");
    }
    for (std::size_t k = 0; k < particleShears_.size(); ++k)
    {
        if (!(particleShears_[k] > 0.0) || (k > 0 && !(particleShears_[k] > particleShears_[k - 1])))
        {
            c.fail("particleShears", "must be positive and increasing (Pa)");
        }
    }
    const std::size_t m = particleShears_.size();
    auto table = [&](const std::string& key)
    {
        const std::vector<double> v = c.getScalarList(key);
        if (v.size() != ratios_.size()*m)
        {
            c.fail(key, "needs one row of " + std::to_string(m) + " values (one per particleShears) for each of the "
                + std::to_string(ratios_.size()) + " ratios: " + std::to_string(ratios_.size()*m) + " values");
        }
        for (std::size_t r = 0; r < ratios_.size(); ++r)
        {
            for (std::size_t k = 1; k < m; ++k)
            {
                if (!(v[r*m + k] > v[r*m + k - 1]))
                {
                    std::ostringstream msg;
                    msg << "row " << r + 1 << " (ratio " << ratios_[r] << ") must rise with the particle strength";
                    c.fail(key, msg.str());
                }
            }
        }
        return v;
    };
    effectiveShears_ = table("effectiveShears");
    effectiveTensiles_ = table("effectiveTensiles");
}


std::pair<std::size_t, double> CalibratedParticleStrength::ratioSegment(double rho) const
{
    const double tolerance = 1e-9;
    if (!(rho >= ratios_.front()*(1 - tolerance) && rho <= ratios_.back()*(1 + tolerance)))
    {
        std::ostringstream msg;
        msg << "a tensile-to-shear ratio of " << rho << " lies outside the calibrated ratios (" << ratios_.front()
            << " to " << ratios_.back() << "): rerun the study at it";
        throw InputError(fileName(), "calibratedCoeffs.ratios", msg.str());
    }
    if (ratios_.size() == 1)
    {
        return {0, 0.0};
    }
    std::size_t k = 1;
    while (k + 1 < ratios_.size() && ratios_[k] < rho)
    {
        ++k;
    }
    return {k, std::clamp((rho - ratios_[k - 1])/(ratios_[k] - ratios_[k - 1]), 0.0, 1.0)};
}


CalibratedParticleStrength::Coefficients CalibratedParticleStrength::at(double rho) const
{
    const auto [k, w] = ratioSegment(rho);
    if (ratios_.size() == 1)
    {
        return {shearSlopes_[0], shearIntercepts_[0], tensileSlopes_[0], tensileIntercepts_[0]};
    }
    auto lerp = [&, k = k, w = w](const std::vector<double>& v) { return v[k - 1] + w*(v[k] - v[k - 1]); };
    return {lerp(shearSlopes_), lerp(shearIntercepts_), lerp(tensileSlopes_), lerp(tensileIntercepts_)};
}


CalibratedParticleStrength::Points CalibratedParticleStrength::pointsAt(double rho) const
{
    const auto [k, w] = ratioSegment(rho);
    const std::size_t m = particleShears_.size();
    Points p;
    p.particleShears = particleShears_;
    for (std::size_t j = 0; j < m; ++j)
    {
        auto lerp = [&, k = k, w = w](const std::vector<double>& v)
        {
            return ratios_.size() == 1 ? v[j] : v[(k - 1)*m + j] + w*(v[k*m + j] - v[(k - 1)*m + j]);
        };
        p.effectiveShears.push_back(lerp(effectiveShears_));
        p.effectiveTensiles.push_back(lerp(effectiveTensiles_));
        p.particleTensiles.push_back(rho*particleShears_[j]);
    }
    return p;
}


BondStrengthPair CalibratedParticleStrength::particle(const BondStrengthPair& e) const
{
    if (!(e.tensile > 0.0 && e.shear > 0.0))
    {
        throw InputError(fileName(), "particleStrengths",
            "calibrated needs positive effective strengths (tensile " + kPa(e.tensile) + ", shear " + kPa(e.shear) + ")");
    }
    const double rho = e.tensile/e.shear;
    BondStrengthPair p;
    double withoutBonds = 0.0;      // S_eff the relation gives at S_p = 0: the confinement's friction
    if (points_)
    {
        const Points q = pointsAt(rho);
        p.shear = alongPolyline(q.effectiveShears, q.particleShears, e.shear);
        withoutBonds = alongPolyline(q.particleShears, q.effectiveShears, 0.0);
    }
    else
    {
        const Coefficients c = at(rho);
        p.shear = (e.shear - c.shearIntercept)/c.shearSlope;
        withoutBonds = c.shearIntercept;
    }
    p.tensile = rho*p.shear;
    if (!(p.shear > 0.0))
    {
        std::ostringstream msg;
        msg << "the calibration cannot give an effective shear strength of " << kPa(e.shear)
            << " on the bond area: the virtual shear test gives " << kPa(withoutBonds)
            << " with no bond strength at all (the confinement's friction)";
        throw InputError(fileName(), points_ ? "calibratedCoeffs.effectiveShears" : "calibratedCoeffs.shearIntercepts",
                         msg.str());
    }
    return p;
}


BondStrengthPair CalibratedParticleStrength::effective(const BondStrengthPair& p) const
{
    if (!(p.tensile > 0.0 && p.shear > 0.0))
    {
        return {0.0, 0.0};
    }
    if (points_)
    {
        const Points q = pointsAt(p.tensile/p.shear);
        return {alongPolyline(q.particleTensiles, q.effectiveTensiles, p.tensile),
                alongPolyline(q.particleShears, q.effectiveShears, p.shear)};
    }
    const Coefficients c = at(p.tensile/p.shear);
    return {c.tensileSlope*p.tensile + c.tensileIntercept, c.shearSlope*p.shear + c.shearIntercept};
}


void CalibratedParticleStrength::checkIce(const IceProperties& ice, const std::string& iceFile) const
{
    const double iceModulus = ice.family(BondFamily::ice).youngsModulus;
    const BondFamilyParameters& freeze = ice.family(BondFamily::freeze);
    auto check = [&](double ratio, double calibrated, const std::string& what, const std::string& entry)
    {
        if (std::abs(ratio/calibrated - 1.0) > 0.02)
        {
            std::ostringstream msg;
            msg << "the calibration holds for freeze-bonds of " << calibrated << " times the ice bonds' modulus "
                << what << "; " << iceFile << " (bondFamilies freeze and ice) gives " << ratio
                << ": rerun the study at that ratio or use particleStrengths direct";
            throw InputError(fileName(), "calibratedCoeffs." + entry, msg.str());
        }
    };
    check(freeze.youngsModulus/iceModulus, modulusRatio_, "(youngsModulus)", "freezeToIceModulusRatio");
    check(freeze.compressionModulusOrYoungs()/iceModulus, compressionRatio_, "in compression (compressionModulus)",
          "freezeCompressionToIceModulusRatio");
}


const std::string& CalibratedParticleStrength::name() const
{
    static const std::string n = "calibrated";
    return n;
}


std::string CalibratedParticleStrength::summary() const
{
    std::ostringstream out;
    out << "particle strengths calibrated (virtual tests at " << kPa(confinement_) << " on the bond area, "
        << ratios_.size() << " ratios T_p/S_p from " << ratios_.front() << " to " << ratios_.back()
        << (points_ ? ", the measured points" : ", straight lines") << ", +- "
        << 100*relativeError_ << " %)";
    return out.str();
}

} // namespace iceDEM
