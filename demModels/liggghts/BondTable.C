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


BondTable::BondTable(LiggghtsInstance& lmp, int capacity)
:
    lmp_(lmp),
    capacity_(capacity)
{
    // property/atom: id group style name vector restart commGhost commReverse defaults...
    std::ostringstream cmd;
    cmd << "fix " << fixId << " all property/atom " << fixId << " vector yes no no";
    for (int k = 0; k < 1 + capacity * slotSize; ++k)
    {
        cmd << " 0";
    }
    lmp_.command(cmd.str());
    fix_ = &lmp_.fix(fixId);
}


double* BondTable::slots(int i) const
{
    // The array is reallocated as atoms arrive, so never keep the row pointer.
    // Its first value is the number of bonds; the slots follow.
    return fix_->array_atom[i] + 1;
}


int BondTable::count(int i) const
{
    return static_cast<int>(fix_->array_atom[i][0]);
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
    const double wanted = static_cast<double>(partnerTagValue);
    const int n = count(i);
    for (int k = 0; k < n; ++k)
    {
        if (s[k * slotSize + partnerTag] == wanted)
        {
            return k;
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
    fix_->array_atom[i][0] = n + 1;
    return true;
}


void BondTable::clear(int i)
{
    double* row = fix_->array_atom[i];
    std::fill(row, row + 1 + capacity_ * slotSize, 0.0);
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
    fix_->array_atom[i][0] = last;
}

} // namespace iceDEM
