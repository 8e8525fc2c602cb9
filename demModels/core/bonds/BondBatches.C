#include "BondBatches.H"

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


void BondBatches::resize(std::size_t count)
{
    size_ = count;
    batches_.resize((count + bondKernelLanes - 1) / bondKernelLanes);
}


void BondBatches::set
(
    std::size_t bond, int a, int b, const BondState& state, const BondStiffness& k, const IntactBounds& intact
)
{
    BondBatch& batch = batches_[bond / bondKernelLanes];
    const std::size_t l = bond % bondKernelLanes;
    batch.a[l] = a;
    batch.b[l] = b;
    batch.loadOfA[l] = batch.loadOfB[l] = 0;
    batch.restLength[l] = state.restLength;
    batch.kNormal[l] = k.normal;
    batch.kNormalCompression[l] = k.normalCompression;
    batch.kShear[l] = k.shear;
    batch.kTwist[l] = k.twist;
    batch.kBending[l] = k.bending;
    batch.twistAngle[l] = state.twistAngle;
    batch.intactNormalForce[l] = intact.normalForce;
    batch.intactShearForce2[l] = intact.shearForce2;
    batch.intactTwistTorque2[l] = intact.twistTorque2;
    batch.intactBendingTorque2[l] = intact.bendingTorque2;
    for (int c = 0; c < 3; ++c)
    {
        batch.shearDisplacement[c][l] = state.shearDisplacement[c];
        batch.bendingAngle[c][l] = state.bendingAngle[c];
    }
}


void BondBatches::copyBond(std::size_t from, std::size_t to)
{
    const BondBatch& source = batches_[from / bondKernelLanes];
    BondBatch& target = batches_[to / bondKernelLanes];
    const std::size_t s = from % bondKernelLanes, t = to % bondKernelLanes;
    for (int (BondBatch::*row)[bondKernelLanes] : {&BondBatch::a, &BondBatch::b, &BondBatch::loadOfA, &BondBatch::loadOfB})
    {
        (target.*row)[t] = (source.*row)[s];
    }
    for (double (BondBatch::*row)[bondKernelLanes] :
        {
            &BondBatch::restLength, &BondBatch::kNormal, &BondBatch::kNormalCompression, &BondBatch::kShear, &BondBatch::kTwist,
            &BondBatch::kBending, &BondBatch::twistAngle, &BondBatch::intactNormalForce,
            &BondBatch::intactShearForce2, &BondBatch::intactTwistTorque2, &BondBatch::intactBendingTorque2
        })
    {
        (target.*row)[t] = (source.*row)[s];
    }
    for (int c = 0; c < 3; ++c)
    {
        target.shearDisplacement[c][t] = source.shearDisplacement[c][s];
        target.bendingAngle[c][t] = source.bendingAngle[c][s];
    }
}


void BondBatches::pad()
{
    for (std::size_t bond = size_; bond < batches_.size() * bondKernelLanes; ++bond)
    {
        copyBond(size_ - 1, bond);
    }
}


void BondBatches::setLoadSlots(std::size_t bond, int slotOfA, int slotOfB)
{
    BondBatch& batch = batches_[bond / bondKernelLanes];
    batch.loadOfA[bond % bondKernelLanes] = slotOfA;
    batch.loadOfB[bond % bondKernelLanes] = slotOfB;
}


void BondBatches::copyHistory(std::size_t bond, BondState& state) const
{
    const BondBatch& batch = batches_[bond / bondKernelLanes];
    const std::size_t l = bond % bondKernelLanes;
    state.twistAngle = batch.twistAngle[l];
    for (int c = 0; c < 3; ++c)
    {
        state.shearDisplacement[c] = batch.shearDisplacement[c][l];
        state.bendingAngle[c] = batch.bendingAngle[c][l];
    }
}

} // namespace iceDEM
