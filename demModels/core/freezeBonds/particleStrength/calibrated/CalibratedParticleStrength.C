#include "CalibratedParticleStrength.H"

#include "Dictionary.H"
#include "IceProperties.H"
#include "InputError.H"

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
            "(cases/common/freezeBondParticleStrengths)");
    }
    const Dictionary& c = d.subDict("calibratedCoeffs");
    c.checkKeys({"tensile", "shear", "confinement", "freezeToIceModulusRatio", "relativeError"});
    auto row = [&](const std::string& key, double& fromTensile, double& fromShear, double& intercept)
    {
        const Dictionary& r = c.subDict(key);
        r.checkKeys({"fromTensile", "fromShear", "intercept"});
        fromTensile = r.getScalar("fromTensile");
        fromShear = r.getScalar("fromShear");
        intercept = r.getScalar("intercept");
    };
    row("tensile", tt_, ts_, bt_);
    row("shear", st_, ss_, bs_);
    if (!(tt_ > 0.0)) c.subDict("tensile").fail("fromTensile", "must be positive: the tensile strength must rise with T_p");
    if (!(ss_ > 0.0)) c.subDict("shear").fail("fromShear", "must be positive: the shear strength must rise with S_p");
    if (!(tt_*ss_ - ts_*st_ > 1e-6*tt_*ss_))
    {
        c.fail("shear", "the relation cannot be inverted (fromTensile*fromShear of the two rows must exceed "
            "their cross terms' product)");
    }
    confinement_ = c.getScalar("confinement");
    if (confinement_ < 0.0) c.fail("confinement", "must not be negative (Pa)");
    modulusRatio_ = c.getScalar("freezeToIceModulusRatio");
    if (!(modulusRatio_ > 0.0)) c.fail("freezeToIceModulusRatio", "must be positive");
    relativeError_ = c.getScalar("relativeError");
    if (relativeError_ < 0.0) c.fail("relativeError", "must not be negative");
}


BondStrengthPair CalibratedParticleStrength::particle(const BondStrengthPair& e) const
{
    const double det = tt_*ss_ - ts_*st_;
    const double t = e.tensile - bt_, s = e.shear - bs_;
    BondStrengthPair p;
    p.tensile = (ss_*t - ts_*s)/det;
    p.shear = (tt_*s - st_*t)/det;
    if (!(p.tensile > 0.0 && p.shear > 0.0))
    {
        std::ostringstream msg;
        msg << "the calibration cannot give effective strengths of " << kPa(e.tensile) << " (tensile) and "
            << kPa(e.shear) << " (shear) on the bond area: they need particle strengths " << kPa(p.tensile)
            << " and " << kPa(p.shear) << " (the intercepts, " << kPa(bt_) << " and " << kPa(bs_)
            << ", are what the confinement alone gives in the virtual tests)";
        throw InputError(fileName(), "calibratedCoeffs", msg.str());
    }
    return p;
}


BondStrengthPair CalibratedParticleStrength::effective(const BondStrengthPair& p) const
{
    return {tt_*p.tensile + ts_*p.shear + bt_, st_*p.tensile + ss_*p.shear + bs_};
}


void CalibratedParticleStrength::checkIce(const IceProperties& ice, const std::string& iceFile) const
{
    const double ratio = ice.family(BondFamily::freeze).youngsModulus/ice.family(BondFamily::ice).youngsModulus;
    if (std::abs(ratio/modulusRatio_ - 1.0) > 0.02)
    {
        std::ostringstream msg;
        msg << "the calibration holds for freeze-bonds of " << modulusRatio_ << " times the ice bonds' modulus; "
            << iceFile << " (bondFamilies freeze and ice) gives " << ratio
            << ": rerun the virtual tests at that ratio or use particleStrengths direct";
        throw InputError(fileName(), "calibratedCoeffs.freezeToIceModulusRatio", msg.str());
    }
}


const std::string& CalibratedParticleStrength::name() const
{
    static const std::string n = "calibrated";
    return n;
}


std::string CalibratedParticleStrength::summary() const
{
    std::ostringstream out;
    out << "particle strengths calibrated (virtual tests at " << kPa(confinement_) << " on the bond area): "
        << "T_eff = " << tt_ << " T_p + " << ts_ << " S_p + " << kPa(bt_) << ", S_eff = " << st_ << " T_p + " << ss_
        << " S_p + " << kPa(bs_) << " (+- " << 100*relativeError_ << " %)";
    return out.str();
}

} // namespace iceDEM
