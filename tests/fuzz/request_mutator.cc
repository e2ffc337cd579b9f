#include "request_mutator.h"

#include <climits>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "fuzz_random.h"
#include "geometry_mutations.h"
#include "google/protobuf/descriptor.h"

namespace freeform::fuzz {
namespace {

using google::protobuf::Descriptor;
using google::protobuf::FieldDescriptor;
using google::protobuf::Message;
using google::protobuf::Reflection;

// Mutants tried before the byte mutator answers (a mutant too large, or
// one that changed nothing).
constexpr int kAttempts = 4;

std::unique_ptr<Message> Parse(const Message& prototype, const uint8_t* data,
                               size_t size) {
  std::unique_ptr<Message> message(prototype.New());
  if (size > static_cast<size_t>(INT_MAX) ||
      !message->ParseFromArray(data, static_cast<int>(size))) {
    return nullptr;
  }
  return message;
}

// Mutate applies one to four changes; true when any changed something.
bool Mutate(Message& request, const MutationLimits& limits,
            FuzzRandom& random) {
  const size_t changes = random.OneIn(2) ? 1 : 1 + random.Below(4);
  bool changed = false;
  for (size_t k = 0; k < changes; ++k) {
    changed |= random.OneIn(2) ? MutateGeometry(request, limits, random)
                               : MutateRandomField(request, limits, random);
  }
  return changed;
}

// Every message inside `message`, itself first.
void CollectMessages(Message& message, std::vector<Message*>& out) {
  out.push_back(&message);
  const Descriptor& type = *message.GetDescriptor();
  const Reflection& r = *message.GetReflection();
  for (int i = 0; i < type.field_count(); ++i) {
    const FieldDescriptor* field = type.field(i);
    if (field->cpp_type() != FieldDescriptor::CPPTYPE_MESSAGE) continue;
    if (field->is_repeated()) {
      for (int k = 0; k < r.FieldSize(message, field); ++k) {
        CollectMessages(*r.MutableRepeatedMessage(&message, field, k), out);
      }
    } else if (r.HasField(message, field)) {
      CollectMessages(*r.MutableMessage(&message, field), out);
    }
  }
}

// MixTopFields swaps each top field of `a` with that of `b` by a coin.
void MixTopFields(Message& a, Message& b, FuzzRandom& random) {
  const Descriptor& type = *a.GetDescriptor();
  std::vector<const FieldDescriptor*> fields;
  for (int i = 0; i < type.field_count(); ++i) {
    if (random.OneIn(2)) fields.push_back(type.field(i));
  }
  a.GetReflection()->SwapFields(&a, &b, fields);
}

}  // namespace

size_t MutateRequest(const Message& prototype, uint8_t* data, size_t size,
                     size_t max_size, uint64_t seed, ByteMutator byte_mutator,
                     const MutationLimits& limits) {
  FuzzRandom random(seed);
  if (random.OneIn(kByteMutationOneIn)) {
    return byte_mutator(data, size, max_size);
  }
  const std::unique_ptr<Message> request = Parse(prototype, data, size);
  if (request == nullptr) return byte_mutator(data, size, max_size);
  const std::string original(reinterpret_cast<const char*>(data), size);
  for (int attempt = 0; attempt < kAttempts; ++attempt) {
    std::unique_ptr<Message> mutant(request->New());
    mutant->CopyFrom(*request);
    if (!Mutate(*mutant, limits, random)) continue;
    std::string bytes;
    if (!mutant->SerializeToString(&bytes) || bytes.size() > max_size ||
        bytes == original) {
      continue;
    }
    std::memcpy(data, bytes.data(), bytes.size());
    return bytes.size();
  }
  return byte_mutator(data, size, max_size);
}

size_t CrossOverRequests(const Message& prototype, const uint8_t* data1,
                         size_t size1, const uint8_t* data2, size_t size2,
                         uint8_t* out, size_t max_out_size, uint64_t seed) {
  FuzzRandom random(seed);
  const std::unique_ptr<Message> first = Parse(prototype, data1, size1);
  const std::unique_ptr<Message> second = Parse(prototype, data2, size2);
  if (first == nullptr || second == nullptr) return 0;
  std::vector<Message*> in_first, in_second;
  CollectMessages(*first, in_first);
  CollectMessages(*second, in_second);
  Message& target = *in_first[random.Below(in_first.size())];
  std::vector<Message*> donors;
  for (Message* message : in_second) {
    if (message->GetDescriptor() == target.GetDescriptor()) {
      donors.push_back(message);
    }
  }
  if (&target == first.get() || donors.empty()) {
    MixTopFields(*first, *second, random);
  } else {
    target.CopyFrom(*donors[random.Below(donors.size())]);
  }
  std::string bytes;
  if (!first->SerializeToString(&bytes) || bytes.size() > max_out_size) {
    return 0;
  }
  std::memcpy(out, bytes.data(), bytes.size());
  return bytes.size();
}

}  // namespace freeform::fuzz
