#include "FreezeBondProperties.H"

#include "Dictionary.H"
#include "FixedSetStrength.H"
#include "InputError.H"

#include <algorithm>
#include <sstream>

namespace iceDEM
{

FreezeBondProperties FreezeBondProperties::read(const std::string& path)
{
    return fromDictionary(Dictionary::readFile(path));
}


FreezeBondProperties FreezeBondProperties::fromDictionary(const Dictionary& d)
{
    d.checkKeys({"submersionTime", "strengthModel", "confinementLineCoeffs", "fixedSetCoeffs", "areaCorrection",
                 "particleStrengths", "calibratedCoeffs"});
    FreezeBondProperties p;
    p.fileName_ = d.fileName();
    const double submersionTime = d.getScalar("submersionTime");
    p.strengthModel_ = FreezeBondStrengthModel::New(d);
    p.strengthModel_->setSubmersionTime(submersionTime);
    p.areaCorrection_ = FreezeBondAreaCorrection::New(d.subDict("areaCorrection"));
    p.particleStrength_ = FreezeBondParticleStrength::New(d);
    return p;
}


void FreezeBondProperties::setSetStrengths(double tensile, double shear)
{
    auto* fixedSet = dynamic_cast<FixedSetStrength*>(strengthModel_.get());
    if (!fixedSet)
    {
        throw InputError(fileName_, "strengthModel", "must be fixedSet to override the set's strengths");
    }
    fixedSet->setStrengths(tensile, shear);
}


FreezeBondStrength FreezeBondProperties::strength(double contactForce, double bondArea) const
{
    const double cf = areaCorrection_->value();
    FreezeBondStrength s;
    s.confinement = std::max(0.0, contactForce)/(cf*bondArea);
    const double realTensile = strengthModel_->tensile(s.confinement);
    const double realShear = strengthModel_->shear(realTensile);
    s.effectiveTensile = cf*realTensile;
    s.effectiveShear = cf*realShear;
    const BondStrengthPair particle = particleStrength_->particle({s.effectiveTensile, s.effectiveShear});
    s.tensile = particle.tensile;
    s.shear = particle.shear;
    return s;
}


std::string FreezeBondProperties::summary() const
{
    std::ostringstream out;
    out << strengthModel_->summary() << "; area correction c_f = " << areaCorrection_->value();
    if (particleStrength_->name() != "direct")
    {
        out << "; " << particleStrength_->summary();
    }
    return out.str();
}

} // namespace iceDEM
