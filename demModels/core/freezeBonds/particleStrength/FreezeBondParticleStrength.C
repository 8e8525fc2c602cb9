#include "FreezeBondParticleStrength.H"

#include "CalibratedParticleStrength.H"
#include "Dictionary.H"
#include "DirectParticleStrength.H"
#include "SelectionTable.H"

namespace iceDEM
{

namespace
{

using ParticleStrengths = SelectionTable<FreezeBondParticleStrength, const Dictionary&>;

const ParticleStrengths particleStrengths
{{
    {"direct", &ParticleStrengths::construct<DirectParticleStrength>},
    {"calibrated", &ParticleStrengths::construct<CalibratedParticleStrength>},
}};

} // namespace


std::unique_ptr<FreezeBondParticleStrength> FreezeBondParticleStrength::New(const Dictionary& d)
{
    if (!d.found("particleStrengths"))
    {
        return std::make_unique<DirectParticleStrength>(d);
    }
    return particleStrengths.New(d, "particleStrengths", d);
}


const std::vector<std::string>& FreezeBondParticleStrength::names()
{
    return particleStrengths.names();
}


void FreezeBondParticleStrength::checkIce(const IceProperties&, const std::string&) const
{}

} // namespace iceDEM
