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
    c.checkKeys({"ratios", "shearSlopes", "shearIntercepts", "tensileSlopes", "tensileIntercepts", "confinement",
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
    shearSlopes_ = column("shearSlopes", true);
    shearIntercepts_ = column("shearIntercepts", false);
    tensileSlopes_ = column("tensileSlopes", true);
    tensileIntercepts_ = column("tensileIntercepts", false);
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


CalibratedParticleStrength::Coefficients CalibratedParticleStrength::at(double rho) const
{
    const double tolerance = 1e-9;
    if (!(rho >= ratios_.front()*(1 - tolerance) && rho <= ratios_.back()*(1 + tolerance)))
    {
        std::ostringstream msg;
        msg << "a tensile-to-shear ratio of " << rho << " lies outside the calibrated ratios (" << ratios_.front()
            << " to " << ratios_.back() << "): rerun the study at it";
        throw InputError(fileName(), "calibratedCoeffs.ratios", msg.str());
    }
    std::size_t k = 1;
    while (k + 1 < ratios_.size() && ratios_[k] < rho)
    {
        ++k;
    }
    if (ratios_.size() == 1)
    {
        return {shearSlopes_[0], shearIntercepts_[0], tensileSlopes_[0], tensileIntercepts_[0]};
    }
    const double w = std::clamp((rho - ratios_[k - 1])/(ratios_[k] - ratios_[k - 1]), 0.0, 1.0);
    auto lerp = [&](const std::vector<double>& v) { return v[k - 1] + w*(v[k] - v[k - 1]); };
    return {lerp(shearSlopes_), lerp(shearIntercepts_), lerp(tensileSlopes_), lerp(tensileIntercepts_)};
}


BondStrengthPair CalibratedParticleStrength::particle(const BondStrengthPair& e) const
{
    if (!(e.tensile > 0.0 && e.shear > 0.0))
    {
        throw InputError(fileName(), "particleStrengths",
            "calibrated needs positive effective strengths (tensile " + kPa(e.tensile) + ", shear " + kPa(e.shear) + ")");
    }
    const double rho = e.tensile/e.shear;
    const Coefficients c = at(rho);
    BondStrengthPair p;
    p.shear = (e.shear - c.shearIntercept)/c.shearSlope;
    p.tensile = rho*p.shear;
    if (!(p.shear > 0.0))
    {
        std::ostringstream msg;
        msg << "the calibration cannot give an effective shear strength of " << kPa(e.shear)
            << " on the bond area: the virtual shear test gives " << kPa(c.shearIntercept)
            << " with no bond strength at all (the confinement's friction)";
        throw InputError(fileName(), "calibratedCoeffs.shearIntercepts", msg.str());
    }
    return p;
}


BondStrengthPair CalibratedParticleStrength::effective(const BondStrengthPair& p) const
{
    if (!(p.tensile > 0.0 && p.shear > 0.0))
    {
        return {0.0, 0.0};
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
        << ratios_.size() << " ratios T_p/S_p from " << ratios_.front() << " to " << ratios_.back() << ", +- "
        << 100*relativeError_ << " %)";
    return out.str();
}

} // namespace iceDEM
