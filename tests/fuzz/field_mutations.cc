#include "field_mutations.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "google/protobuf/descriptor.h"
#include "google/protobuf/reflection.h"

namespace freeform::fuzz {
namespace {

using google::protobuf::Descriptor;
using google::protobuf::EnumDescriptor;
using google::protobuf::FieldDescriptor;
using google::protobuf::Message;
using google::protobuf::Reflection;

// How deep the search for a field goes, and how many elements of one
// repeated message field it looks into: requests nest five levels
// (request, curve, bspline, points, coordinates).
constexpr int kMaxDepth = 8;
constexpr int kMaxVisitedElements = 8;

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kMax = std::numeric_limits<double>::max();
constexpr double kMinNormal = std::numeric_limits<double>::min();
constexpr double kDenormalMin = std::numeric_limits<double>::denorm_min();

constexpr double kBoundaryDoubles[] = {0.0,
                                       -0.0,
                                       1.0,
                                       -1.0,
                                       2.0,
                                       0.5,
                                       -0.5,
                                       3.0,
                                       1.0 / 3.0,
                                       2147483647.0,
                                       2147483648.0,
                                       -2147483648.0,
                                       4294967296.0,
                                       9007199254740992.0,
                                       9223372036854775808.0,
                                       -9223372036854775808.0,
                                       18446744073709551616.0,
                                       1e10,
                                       -1e10,
                                       1e15,
                                       1e20,
                                       1e50,
                                       1e100,
                                       1e154,
                                       1e155,
                                       1e200,
                                       -1e200,
                                       1e300,
                                       -1e300,
                                       kMax,
                                       -kMax,
                                       1e-10,
                                       1e-15,
                                       1e-17,
                                       1e-50,
                                       1e-154,
                                       1e-155,
                                       1e-200,
                                       1e-300,
                                       -1e-300,
                                       1e-308,
                                       kMinNormal,
                                       1e-310,
                                       -1e-310,
                                       kDenormalMin,
                                       -kDenormalMin,
                                       std::numeric_limits<double>::quiet_NaN(),
                                       kInf,
                                       -kInf};

// Exponents at which double arithmetic changes behaviour: squares
// underflow or overflow past 1e+-154, cubes past 1e+-103, fourth powers
// past 1e+-77, and 1e+-300 is near the end of the range.
constexpr int kExtremeExponents[] = {1,  2,  4,   8,   10,  15,  16,  20,
                                     50, 77, 100, 103, 154, 155, 200, 300};

constexpr uint64_t kBoundaryIntegers[] = {0,
                                          1,
                                          2,
                                          3,
                                          4,
                                          5,
                                          7,
                                          8,
                                          15,
                                          16,
                                          17,
                                          18,
                                          31,
                                          32,
                                          33,
                                          63,
                                          64,
                                          65,
                                          255,
                                          256,
                                          1023,
                                          1024,
                                          1025,
                                          4095,
                                          4096,
                                          8191,
                                          8192,
                                          8193,
                                          65535,
                                          65536,
                                          65537,
                                          uint64_t{0x7fffffff},
                                          uint64_t{0x80000000},
                                          uint64_t{0xfffffffe},
                                          uint64_t{0xffffffff},
                                          uint64_t{1} << 32,
                                          (uint64_t{1} << 32) + 1,
                                          uint64_t{1} << 53,
                                          uint64_t{0x7fffffffffffffff},
                                          uint64_t{0x8000000000000000},
                                          ~uint64_t{0},
                                          ~uint64_t{1},
                                          ~uint64_t{0x7fffffff}};

// A value of `values` at random, whose span may be empty.
template <typename T>
bool PickFrom(absl::Span<const T> values, FuzzRandom& random, T& out) {
  if (values.empty()) return false;
  out = random.Pick(values);
  return true;
}

double Perturb(double value, FuzzRandom& random) {
  switch (random.Below(4)) {
    case 0: {  // a few ulps either way
      const double towards = random.OneIn(2) ? kInf : -kInf;
      for (size_t k = 1 + random.Below(4); k > 0; --k) {
        value = std::nextafter(value, towards);
      }
      return value;
    }
    case 1: {  // a relative change of 1e-15 .. 1e-3
      constexpr double kRelative[] = {1e-15, 1e-12, 1e-9, 1e-6, 1e-3};
      const double change = random.Pick(absl::MakeConstSpan(kRelative));
      return value * (1.0 + (random.OneIn(2) ? change : -change));
    }
    case 2:  // an absolute change, tiny or not
      return value + (random.OneIn(2) ? 1.0 : -1.0) *
                         random.Pick(absl::MakeConstSpan(
                             {kDenormalMin, 1e-300, 1e-12, 1e-6, 0.5, 1.0}));
    default:
      return -value;
  }
}

// MutateLength grows, shrinks or reorders `values`.
template <typename T>
bool MutateLength(std::vector<T>& values, const MutationLimits& limits,
                  FuzzRandom& random) {
  const size_t size = values.size();
  const size_t room =
      size >= static_cast<size_t>(limits.max_repeated)
          ? 0
          : std::min<size_t>(static_cast<size_t>(limits.max_growth),
                             static_cast<size_t>(limits.max_repeated) - size);
  if (size == 0) {
    if (room == 0) return false;
    values.assign(1 + random.Below(std::min<size_t>(room, 4)), T{});
    return true;
  }
  switch (random.Below(9)) {
    case 0: {  // duplicate one element in place
      if (room == 0) return false;
      const size_t at = random.Below(size);
      values.insert(values.begin() + static_cast<ptrdiff_t>(at), values[at]);
      return true;
    }
    case 1: {  // append copies of one element
      if (room == 0) return false;
      const T copy = values[random.Below(size)];
      values.insert(values.end(), 1 + random.Below(room), copy);
      return true;
    }
    case 2: {  // repeat the head
      if (room == 0) return false;
      const size_t copies = std::min(size, room);
      values.insert(values.end(), values.begin(),
                    values.begin() + static_cast<ptrdiff_t>(copies));
      return true;
    }
    case 3:  // drop one element
      values.erase(values.begin() + static_cast<ptrdiff_t>(random.Below(size)));
      return true;
    case 4:  // truncate to 0 or 1
      values.resize(random.Below(2));
      return true;
    case 5:  // truncate anywhere
      values.resize(random.Below(size));
      return true;
    case 6:
      std::reverse(values.begin(), values.end());
      return size > 1;
    case 7:
      std::sort(values.begin(), values.end());
      return size > 1;
    default:  // all equal
      values.assign(size, values[random.Below(size)]);
      return size > 1;
  }
}

// Integers and enums are kept as 64 bits until written back.
uint64_t MutateEnum(const EnumDescriptor& type, FuzzRandom& random) {
  if (random.OneIn(4)) {
    // Unknown numbers: proto3 keeps them, the server must refuse them.
    int max = 0;
    for (int i = 0; i < type.value_count(); ++i) {
      max = std::max(max, type.value(i)->number());
    }
    const int64_t unknown[] = {max + 1, -1, 1000,
                               std::numeric_limits<int32_t>::max(),
                               std::numeric_limits<int32_t>::min()};
    return static_cast<uint64_t>(random.Pick(absl::MakeConstSpan(unknown)));
  }
  return static_cast<uint64_t>(static_cast<int64_t>(
      type.value(static_cast<int>(random.Below(type.value_count())))
          ->number()));
}

// The value of one scalar element as 64 bits (doubles and floats apart).
uint64_t GetInteger(const Message& message, const FieldDescriptor& field,
                    int index) {
  const Reflection& r = *message.GetReflection();
  const bool repeated = field.is_repeated();
  switch (field.cpp_type()) {
    case FieldDescriptor::CPPTYPE_INT32:
      return static_cast<uint64_t>(static_cast<int64_t>(
          repeated ? r.GetRepeatedInt32(message, &field, index)
                   : r.GetInt32(message, &field)));
    case FieldDescriptor::CPPTYPE_INT64:
      return static_cast<uint64_t>(
          repeated ? r.GetRepeatedInt64(message, &field, index)
                   : r.GetInt64(message, &field));
    case FieldDescriptor::CPPTYPE_UINT32:
      return repeated ? r.GetRepeatedUInt32(message, &field, index)
                      : r.GetUInt32(message, &field);
    case FieldDescriptor::CPPTYPE_UINT64:
      return repeated ? r.GetRepeatedUInt64(message, &field, index)
                      : r.GetUInt64(message, &field);
    case FieldDescriptor::CPPTYPE_BOOL:
      return repeated ? r.GetRepeatedBool(message, &field, index)
                      : r.GetBool(message, &field);
    case FieldDescriptor::CPPTYPE_ENUM:
      return static_cast<uint64_t>(static_cast<int64_t>(
          repeated ? r.GetRepeatedEnumValue(message, &field, index)
                   : r.GetEnumValue(message, &field)));
    default:
      return 0;
  }
}

// SetInteger writes one scalar element (index -1: append to a repeated
// field), casting to the field's type.
void SetInteger(Message& message, const FieldDescriptor& field, int index,
                uint64_t value) {
  const Reflection& r = *message.GetReflection();
  const bool add = field.is_repeated() && index < 0;
  const bool set_element = field.is_repeated() && index >= 0;
  switch (field.cpp_type()) {
    case FieldDescriptor::CPPTYPE_INT32: {
      const auto v = static_cast<int32_t>(value);
      if (add) return r.AddInt32(&message, &field, v);
      if (set_element) return r.SetRepeatedInt32(&message, &field, index, v);
      return r.SetInt32(&message, &field, v);
    }
    case FieldDescriptor::CPPTYPE_INT64: {
      const auto v = static_cast<int64_t>(value);
      if (add) return r.AddInt64(&message, &field, v);
      if (set_element) return r.SetRepeatedInt64(&message, &field, index, v);
      return r.SetInt64(&message, &field, v);
    }
    case FieldDescriptor::CPPTYPE_UINT32: {
      const auto v = static_cast<uint32_t>(value);
      if (add) return r.AddUInt32(&message, &field, v);
      if (set_element) return r.SetRepeatedUInt32(&message, &field, index, v);
      return r.SetUInt32(&message, &field, v);
    }
    case FieldDescriptor::CPPTYPE_UINT64:
      if (add) return r.AddUInt64(&message, &field, value);
      if (set_element) {
        return r.SetRepeatedUInt64(&message, &field, index, value);
      }
      return r.SetUInt64(&message, &field, value);
    case FieldDescriptor::CPPTYPE_BOOL: {
      const bool v = (value & 1) != 0;
      if (add) return r.AddBool(&message, &field, v);
      if (set_element) return r.SetRepeatedBool(&message, &field, index, v);
      return r.SetBool(&message, &field, v);
    }
    case FieldDescriptor::CPPTYPE_ENUM: {
      const auto v = static_cast<int>(static_cast<int32_t>(value));
      if (add) return r.AddEnumValue(&message, &field, v);
      if (set_element) {
        return r.SetRepeatedEnumValue(&message, &field, index, v);
      }
      return r.SetEnumValue(&message, &field, v);
    }
    default:
      return;
  }
}

uint64_t MutateIntegerOf(const FieldDescriptor& field, uint64_t value,
                         FuzzRandom& random) {
  if (field.cpp_type() == FieldDescriptor::CPPTYPE_BOOL) return value ^ 1;
  if (field.cpp_type() == FieldDescriptor::CPPTYPE_ENUM) {
    return MutateEnum(*field.enum_type(), random);
  }
  return MutateInteger(value, random);
}

double GetDouble(const Message& message, const FieldDescriptor& field,
                 int index) {
  const Reflection& r = *message.GetReflection();
  if (field.cpp_type() == FieldDescriptor::CPPTYPE_FLOAT) {
    return field.is_repeated() ? r.GetRepeatedFloat(message, &field, index)
                               : r.GetFloat(message, &field);
  }
  return field.is_repeated() ? r.GetRepeatedDouble(message, &field, index)
                             : r.GetDouble(message, &field);
}

std::vector<double> GetDoubles(const Message& message,
                               const FieldDescriptor& field) {
  std::vector<double> values(
      static_cast<size_t>(message.GetReflection()->FieldSize(message, &field)));
  for (size_t i = 0; i < values.size(); ++i) {
    values[i] = GetDouble(message, field, static_cast<int>(i));
  }
  return values;
}

void SetDoubles(Message& message, const FieldDescriptor& field,
                const std::vector<double>& values) {
  const Reflection& r = *message.GetReflection();
  r.ClearField(&message, &field);
  for (double value : values) {
    if (field.cpp_type() == FieldDescriptor::CPPTYPE_FLOAT) {
      r.AddFloat(&message, &field, static_cast<float>(value));
    } else {
      r.AddDouble(&message, &field, value);
    }
  }
}

void SetDouble(Message& message, const FieldDescriptor& field, double value) {
  const Reflection& r = *message.GetReflection();
  if (field.cpp_type() == FieldDescriptor::CPPTYPE_FLOAT) {
    r.SetFloat(&message, &field, static_cast<float>(value));
  } else {
    r.SetDouble(&message, &field, value);
  }
}

bool IsFloating(const FieldDescriptor& field) {
  return field.cpp_type() == FieldDescriptor::CPPTYPE_DOUBLE ||
         field.cpp_type() == FieldDescriptor::CPPTYPE_FLOAT;
}

// A repeated integer (bool, enum) field: its elements changed, its length
// changed, or it is reordered.
bool MutateRepeatedIntegers(Message& message, const FieldDescriptor& field,
                            const MutationLimits& limits, FuzzRandom& random) {
  const Reflection& r = *message.GetReflection();
  const int size = r.FieldSize(message, &field);
  if (size > 0 && !random.OneIn(3)) {
    const int at = static_cast<int>(random.Below(static_cast<size_t>(size)));
    SetInteger(message, field, at,
               MutateIntegerOf(field, GetInteger(message, field, at), random));
    return true;
  }
  std::vector<uint64_t> values(static_cast<size_t>(size));
  for (int i = 0; i < size; ++i) {
    values[static_cast<size_t>(i)] = GetInteger(message, field, i);
  }
  if (!MutateLength(values, limits, random)) return false;
  r.ClearField(&message, &field);
  for (uint64_t value : values) SetInteger(message, field, -1, value);
  return true;
}

// A scalar field, repeated or not, of any type.
bool MutateScalar(Message& message, const FieldDescriptor& field,
                  absl::Span<const double> pool, const MutationLimits& limits,
                  FuzzRandom& random) {
  const Reflection& r = *message.GetReflection();
  if (field.is_repeated()) {
    if (IsFloating(field)) {
      std::vector<double> values = GetDoubles(message, field);
      if (!MutateDoubles(values, pool, limits, random)) return false;
      SetDoubles(message, field, values);
      return true;
    }
    return MutateRepeatedIntegers(message, field, limits, random);
  }
  // A proto3 `optional` (or oneof) member is sometimes cleared.
  if (field.has_presence() && r.HasField(message, &field) && random.OneIn(6)) {
    r.ClearField(&message, &field);
    return true;
  }
  if (IsFloating(field)) {
    SetDouble(message, field,
              MutateDouble(GetDouble(message, field, -1), pool, random));
  } else {
    SetInteger(message, field, -1,
               MutateIntegerOf(field, GetInteger(message, field, -1), random));
  }
  return true;
}

// A repeated message field: an element duplicated, dropped, added empty,
// two swapped, or the field truncated to 0 or 1 element.
bool MutateRepeatedMessages(Message& message, const FieldDescriptor& field,
                            const MutationLimits& limits, FuzzRandom& random) {
  const Reflection& r = *message.GetReflection();
  const int size = r.FieldSize(message, &field);
  const bool room = size < limits.max_repeated;
  const auto at = [&] {
    return static_cast<int>(random.Below(static_cast<size_t>(size)));
  };
  switch (size == 0 ? 0 : random.Below(5)) {
    case 0:  // add an empty element
      if (!room) return false;
      r.AddMessage(&message, &field);
      return true;
    case 1: {  // duplicate an element at the end
      if (!room) return false;
      const Message& copy = r.GetRepeatedMessage(message, &field, at());
      std::unique_ptr<Message> saved(copy.New());
      saved->CopyFrom(copy);
      r.AddMessage(&message, &field)->CopyFrom(*saved);
      return true;
    }
    case 2: {  // drop an element
      r.SwapElements(&message, &field, at(), size - 1);
      r.RemoveLast(&message, &field);
      return true;
    }
    case 3:  // swap two
      r.SwapElements(&message, &field, at(), at());
      return size > 1;
    default: {  // truncate to 0 or 1
      const int keep = static_cast<int>(random.Below(2));
      while (r.FieldSize(message, &field) > keep) {
        r.RemoveLast(&message, &field);
      }
      return true;
    }
  }
}

// A message field: a set one is cleared, an unset one created empty (a
// oneof member then replaces the one set).
bool MutateMessageField(Message& message, const FieldDescriptor& field,
                        const MutationLimits& limits, FuzzRandom& random) {
  const Reflection& r = *message.GetReflection();
  if (field.is_repeated()) {
    return MutateRepeatedMessages(message, field, limits, random);
  }
  if (r.HasField(message, &field)) {
    r.ClearField(&message, &field);
  } else {
    r.MutableMessage(&message, &field);
  }
  return true;
}

// Where a mutation may happen: one field of one message.
struct FieldSite {
  Message* message;
  const FieldDescriptor* field;
};

void CollectSites(Message& message, int depth, std::vector<FieldSite>& sites) {
  const Descriptor& type = *message.GetDescriptor();
  const Reflection& r = *message.GetReflection();
  for (int i = 0; i < type.field_count(); ++i) {
    const FieldDescriptor* field = type.field(i);
    sites.push_back({&message, field});
    if (field->cpp_type() != FieldDescriptor::CPPTYPE_MESSAGE ||
        depth >= kMaxDepth) {
      continue;
    }
    if (field->is_repeated()) {
      const int size =
          std::min(r.FieldSize(message, field), kMaxVisitedElements);
      for (int k = 0; k < size; ++k) {
        CollectSites(*r.MutableRepeatedMessage(&message, field, k), depth + 1,
                     sites);
      }
    } else if (r.HasField(message, field)) {
      CollectSites(*r.MutableMessage(&message, field), depth + 1, sites);
    }
  }
}

void CollectDoublesInto(const Message& message, size_t cap,
                        std::vector<double>& out) {
  const Descriptor& type = *message.GetDescriptor();
  const Reflection& r = *message.GetReflection();
  for (int i = 0; i < type.field_count() && out.size() < cap; ++i) {
    const FieldDescriptor* field = type.field(i);
    if (field->cpp_type() == FieldDescriptor::CPPTYPE_MESSAGE) {
      if (field->is_repeated()) {
        for (int k = 0; k < r.FieldSize(message, field); ++k) {
          CollectDoublesInto(r.GetRepeatedMessage(message, field, k), cap, out);
        }
      } else if (r.HasField(message, field)) {
        CollectDoublesInto(r.GetMessage(message, field), cap, out);
      }
    } else if (IsFloating(*field)) {
      if (!field->is_repeated()) {
        if (r.HasField(message, field)) {
          out.push_back(GetDouble(message, *field, -1));
        }
        continue;
      }
      for (int k = 0; k < r.FieldSize(message, field) && out.size() < cap;
           ++k) {
        out.push_back(GetDouble(message, *field, k));
      }
    }
  }
}

}  // namespace

double BoundaryDouble(FuzzRandom& random) {
  return random.Pick(absl::MakeConstSpan(kBoundaryDoubles));
}

double ExtremePowerOfTen(FuzzRandom& random) {
  const int exponent = random.Pick(absl::MakeConstSpan(kExtremeExponents));
  return std::pow(10.0, random.OneIn(2) ? exponent : -exponent);
}

double MutateDouble(double value, absl::Span<const double> pool,
                    FuzzRandom& random) {
  switch (random.Below(10)) {
    case 0:
    case 1:
    case 2:
      return BoundaryDouble(random);
    case 3:
    case 4:
      return Perturb(value, random);
    case 5:
      return value * ExtremePowerOfTen(random);
    case 6:
    case 7: {
      double copy = 0.0;
      if (!PickFrom(pool, random, copy)) return BoundaryDouble(random);
      return random.OneIn(4) ? Perturb(copy, random) : copy;
    }
    case 8:
      return static_cast<double>(random.Between(-4, 4));
    default:
      return 8.0 * random.Unit() - 4.0;
  }
}

uint64_t MutateInteger(uint64_t value, FuzzRandom& random) {
  switch (random.Below(4)) {
    case 0:
    case 1:
      return random.Pick(absl::MakeConstSpan(kBoundaryIntegers));
    case 2:
      return value + static_cast<uint64_t>(random.Between(-3, 3));
    default:
      return static_cast<uint64_t>(random.Between(0, 20));
  }
}

std::vector<double> CollectDoubles(const Message& message, size_t cap) {
  std::vector<double> out;
  CollectDoublesInto(message, cap, out);
  return out;
}

bool MutateDoubles(std::vector<double>& values, absl::Span<const double> pool,
                   const MutationLimits& limits, FuzzRandom& random) {
  if (!values.empty() && !random.OneIn(3)) {
    double& value = values[random.Below(values.size())];
    value = MutateDouble(value, pool, random);
    return true;
  }
  return MutateLength(values, limits, random);
}

bool MutateRandomField(Message& message, const MutationLimits& limits,
                       FuzzRandom& random) {
  std::vector<FieldSite> sites;
  CollectSites(message, 0, sites);
  if (sites.empty()) return false;
  const FieldSite site = sites[random.Below(sites.size())];
  const std::vector<double> pool = CollectDoubles(message, 4096);
  if (site.field->cpp_type() == FieldDescriptor::CPPTYPE_MESSAGE) {
    return MutateMessageField(*site.message, *site.field, limits, random);
  }
  return MutateScalar(*site.message, *site.field, pool, limits, random);
}

}  // namespace freeform::fuzz
