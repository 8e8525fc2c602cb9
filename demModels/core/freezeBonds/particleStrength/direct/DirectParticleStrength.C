#include "DirectParticleStrength.H"

#include "Dictionary.H"

namespace iceDEM
{

DirectParticleStrength::DirectParticleStrength(const Dictionary& d)
:
    FreezeBondParticleStrength(d.fileName())
{}


const std::string& DirectParticleStrength::name() const
{
    static const std::string n = "direct";
    return n;
}


std::string DirectParticleStrength::summary() const
{
    return "particle strengths direct (the effective strengths on the bonds)";
}

} // namespace iceDEM
