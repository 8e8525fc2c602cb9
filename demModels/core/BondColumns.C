#include "BondColumns.H"

namespace iceDEM
{

KernelAtom kernelAtomOf(const ParticleState& p)
{
    KernelAtom atom;
    for (int c = 0; c < 3; ++c)
    {
        atom.position[c] = p.position[c];
        atom.velocity[c] = p.velocity[c];
        atom.angularVelocity[c] = p.angularVelocity[c];
    }
    atom.radius = p.radius;
    atom.mass = p.mass;
    return atom;
}


std::array<std::vector<double>*, 16> BondColumns::doubleColumns()
{
    return
    {
        &restLength_, &kNormal_, &kShear_, &kTwist_, &kBending_, &twistAngle_,
        &shearDisplacement_[0], &shearDisplacement_[1], &shearDisplacement_[2],
        &bendingAngle_[0], &bendingAngle_[1], &bendingAngle_[2],
        &intactNormalForce_, &intactShearForce2_, &intactTwistTorque2_, &intactBendingTorque2_
    };
}


void BondColumns::resize(std::size_t count)
{
    size_ = count;
    const std::size_t padded = (count + bondKernelLanes - 1) / bondKernelLanes * bondKernelLanes;
    for (std::vector<int>* column : {&a_, &b_})
    {
        column->resize(padded);
    }
    for (std::vector<double>* column : doubleColumns())
    {
        column->resize(padded);
    }
}


void BondColumns::set
(
    std::size_t bond, int a, int b, const BondState& state, const BondStiffness& k, const IntactBounds& intact
)
{
    a_[bond] = a;
    b_[bond] = b;
    restLength_[bond] = state.restLength;
    kNormal_[bond] = k.normal;
    kShear_[bond] = k.shear;
    kTwist_[bond] = k.twist;
    kBending_[bond] = k.bending;
    twistAngle_[bond] = state.twistAngle;
    intactNormalForce_[bond] = intact.normalForce;
    intactShearForce2_[bond] = intact.shearForce2;
    intactTwistTorque2_[bond] = intact.twistTorque2;
    intactBendingTorque2_[bond] = intact.bendingTorque2;
    for (int c = 0; c < 3; ++c)
    {
        shearDisplacement_[c][bond] = state.shearDisplacement[c];
        bendingAngle_[c][bond] = state.bendingAngle[c];
    }
}


void BondColumns::pad()
{
    if (size_ == 0)
    {
        return;
    }
    const std::size_t last = size_ - 1;
    for (std::size_t bond = size_; bond < a_.size(); ++bond)
    {
        a_[bond] = a_[last];
        b_[bond] = b_[last];
        for (std::vector<double>* column : doubleColumns())
        {
            (*column)[bond] = (*column)[last];
        }
    }
}


void BondColumns::copyHistory(std::size_t bond, BondState& state) const
{
    state.twistAngle = twistAngle_[bond];
    for (int c = 0; c < 3; ++c)
    {
        state.shearDisplacement[c] = shearDisplacement_[c][bond];
        state.bendingAngle[c] = bendingAngle_[c][bond];
    }
}


BondColumnsView BondColumns::view(const KernelAtom* atoms)
{
    return
    {
        atoms, a_.data(), b_.data(), restLength_.data(), kNormal_.data(), kShear_.data(),
        kTwist_.data(), kBending_.data(), twistAngle_.data(),
        {shearDisplacement_[0].data(), shearDisplacement_[1].data(), shearDisplacement_[2].data()},
        {bendingAngle_[0].data(), bendingAngle_[1].data(), bendingAngle_[2].data()},
        intactNormalForce_.data(), intactShearForce2_.data(), intactTwistTorque2_.data(),
        intactBendingTorque2_.data(),
        nullptr, nullptr, nullptr   // the loads: the caller's
    };
}

} // namespace iceDEM
