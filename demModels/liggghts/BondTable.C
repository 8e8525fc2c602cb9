#include "BondTable.H"

#include "LiggghtsInstance.H"

#include "fix.h"

#include <sstream>

namespace iceDEM
{

namespace
{

enum Field
{
    partnerTag = 0, familyId = 1, restLength = 2,
    shearX = 3, twist = 6, bendX = 7, tensile = 10, shear = 11
};

} // namespace


BondTable::BondTable(LiggghtsInstance& lmp, int capacity, bool create)
:
    lmp_(lmp),
    capacity_(capacity)
{
    if (create)
    {
        // property/atom: id group style name vector restart commGhost commReverse defaults...
        std::ostringstream cmd;
        cmd << "fix " << fixId << " all property/atom " << fixId << " vector yes no no";
        for (int k = 0; k < capacity * slotSize; ++k)
        {
            cmd << " 0";
        }
        lmp_.command(cmd.str());
    }
    fix_ = &lmp_.fix(fixId);   // throws if missing
}


BondTable::BondTable(LiggghtsInstance& lmp, int capacity)
:
    BondTable(lmp, capacity, true)
{}


BondTable BondTable::attach(LiggghtsInstance& lmp, int capacity)
{
    return BondTable(lmp, capacity, false);
}


double* BondTable::slots(int i) const
{
    // The array is reallocated as atoms arrive, so never keep the row pointer.
    return fix_->array_atom[i];
}


int BondTable::count(int i) const
{
    const double* s = slots(i);
    int n = 0;
    while (n < capacity_ && s[n * slotSize + partnerTag] > 0.0)
    {
        ++n;
    }
    return n;
}


long BondTable::partner(int i, int slot) const
{
    return static_cast<long>(slots(i)[slot * slotSize + partnerTag]);
}


BondState BondTable::read(int i, int slot, long ownTag) const
{
    const double* s = slots(i) + slot * slotSize;
    const long other = static_cast<long>(s[partnerTag]);
    BondState b;
    b.tagA = std::min(ownTag, other);
    b.tagB = std::max(ownTag, other);
    b.family = static_cast<BondFamily>(static_cast<int>(s[familyId]));
    b.restLength = s[restLength];
    b.shearDisplacement = Vec3(s[shearX], s[shearX + 1], s[shearX + 2]);
    b.twistAngle = s[twist];
    b.bendingAngle = Vec3(s[bendX], s[bendX + 1], s[bendX + 2]);
    b.tensileStrength = s[tensile];
    b.shearStrength = s[shear];
    return b;
}


void BondTable::write(int i, int slot, const BondState& b, long ownTag)
{
    double* s = slots(i) + slot * slotSize;
    s[partnerTag] = static_cast<double>(ownTag == b.tagA ? b.tagB : b.tagA);
    s[familyId] = static_cast<double>(static_cast<int>(b.family));
    s[restLength] = b.restLength;
    for (int k = 0; k < 3; ++k)
    {
        s[shearX + k] = b.shearDisplacement[k];
        s[bendX + k] = b.bendingAngle[k];
    }
    s[twist] = b.twistAngle;
    s[tensile] = b.tensileStrength;
    s[shear] = b.shearStrength;
}


int BondTable::find(int i, long partnerTagValue) const
{
    const double* s = slots(i);
    for (int k = 0; k < capacity_; ++k)
    {
        const long p = static_cast<long>(s[k * slotSize + partnerTag]);
        if (p == partnerTagValue)
        {
            return k;
        }
        if (p == 0)
        {
            break;
        }
    }
    return -1;
}


bool BondTable::add(int i, const BondState& b, long ownTag)
{
    const int n = count(i);
    if (n >= capacity_)
    {
        return false;
    }
    write(i, n, b, ownTag);
    return true;
}


void BondTable::clear(int i)
{
    double* s = slots(i);
    std::fill(s, s + capacity_ * slotSize, 0.0);
}


void BondTable::remove(int i, int slot)
{
    double* s = slots(i);
    const int last = count(i) - 1;
    if (slot != last)
    {
        std::copy(s + last * slotSize, s + (last + 1) * slotSize, s + slot * slotSize);
    }
    std::fill(s + last * slotSize, s + (last + 1) * slotSize, 0.0);
}

} // namespace iceDEM
