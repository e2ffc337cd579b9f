#include "proto_json.h"

#include <google/protobuf/descriptor.h>
#include <google/protobuf/reflection.h>
#include <google/protobuf/util/json_util.h>

#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <type_traits>
#include <vector>

#include "absl/strings/escaping.h"
#include "absl/strings/str_cat.h"

namespace freeform::server {
namespace {

using google::protobuf::Descriptor;
using google::protobuf::FieldDescriptor;
using google::protobuf::Message;
using google::protobuf::Reflection;

// HandledByProtobuf is true for the messages protobuf's writer must write:
// the well-known types (their JSON has special forms) and messages with a
// map field.
bool HandledByProtobuf(const Descriptor& type) {
  if (type.file()->package() == "google.protobuf") return true;
  for (int i = 0; i < type.field_count(); ++i) {
    if (type.field(i)->is_map()) return true;
  }
  return false;
}

// The longest text of a double or a float: "-2.2250738585072014e-308".
constexpr size_t kMaxNumberChars = 32;

template <typename Number>
void AppendFloatingPoint(Number value, std::string& out) {
  if (std::isnan(value)) {
    out += "\"NaN\"";
  } else if (std::isinf(value)) {
    out += value > 0 ? "\"Infinity\"" : "\"-Infinity\"";
  } else {
    // Written in place: a string's resize within its capacity is cheap,
    // a temporary buffer's append is not (a third of the time of an array).
    const size_t size = out.size();
    out.resize(size + kMaxNumberChars);
    const std::to_chars_result written =
        std::to_chars(out.data() + size, out.data() + out.size(), value);
    out.resize(static_cast<size_t>(written.ptr - out.data()));
  }
}

template <typename Integer>
void AppendInteger(Integer value, bool quoted, std::string& out) {
  std::array<char, 24> buffer;
  const std::to_chars_result written =
      std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
  if (quoted) out += '"';
  out.append(buffer.data(), written.ptr);
  if (quoted) out += '"';
}

void AppendEnum(const FieldDescriptor& field, int number, std::string& out) {
  const google::protobuf::EnumValueDescriptor* value =
      field.enum_type()->FindValueByNumber(number);
  if (value == nullptr) {
    AppendInteger(number, /*quoted=*/false, out);
  } else {
    AppendJsonString(value->name(), out);
  }
}

// The JSON of each element of a repeated field, or of a singular one.
class FieldWriter {
 public:
  FieldWriter(const Message& message, const FieldDescriptor& field,
              std::string& out)
      : message_(message),
        reflection_(*message.GetReflection()),
        field_(field),
        out_(out) {}

  absl::Status WriteSingular() {
    switch (field_.cpp_type()) {
      case FieldDescriptor::CPPTYPE_INT32:
        AppendInteger(reflection_.GetInt32(message_, &field_), false, out_);
        break;
      case FieldDescriptor::CPPTYPE_UINT32:
        AppendInteger(reflection_.GetUInt32(message_, &field_), false, out_);
        break;
      case FieldDescriptor::CPPTYPE_INT64:
        AppendInteger(reflection_.GetInt64(message_, &field_), true, out_);
        break;
      case FieldDescriptor::CPPTYPE_UINT64:
        AppendInteger(reflection_.GetUInt64(message_, &field_), true, out_);
        break;
      case FieldDescriptor::CPPTYPE_DOUBLE:
        AppendFloatingPoint(reflection_.GetDouble(message_, &field_), out_);
        break;
      case FieldDescriptor::CPPTYPE_FLOAT:
        AppendFloatingPoint(reflection_.GetFloat(message_, &field_), out_);
        break;
      case FieldDescriptor::CPPTYPE_BOOL:
        out_ += reflection_.GetBool(message_, &field_) ? "true" : "false";
        break;
      case FieldDescriptor::CPPTYPE_ENUM:
        AppendEnum(field_, reflection_.GetEnumValue(message_, &field_), out_);
        break;
      case FieldDescriptor::CPPTYPE_STRING:
        AppendText(reflection_.GetString(message_, &field_));
        break;
      case FieldDescriptor::CPPTYPE_MESSAGE:
        return AppendMessageJson(reflection_.GetMessage(message_, &field_),
                                 out_);
    }
    return absl::OkStatus();
  }

  absl::Status WriteRepeated() {
    out_ += '[';
    switch (field_.cpp_type()) {
      case FieldDescriptor::CPPTYPE_INT32:
        WriteEach<int32_t>([&](int32_t v) { AppendInteger(v, false, out_); });
        break;
      case FieldDescriptor::CPPTYPE_UINT32:
        WriteEach<uint32_t>([&](uint32_t v) { AppendInteger(v, false, out_); });
        break;
      case FieldDescriptor::CPPTYPE_INT64:
        WriteEach<int64_t>([&](int64_t v) { AppendInteger(v, true, out_); });
        break;
      case FieldDescriptor::CPPTYPE_UINT64:
        WriteEach<uint64_t>([&](uint64_t v) { AppendInteger(v, true, out_); });
        break;
      case FieldDescriptor::CPPTYPE_DOUBLE:
        WriteEach<double>([&](double v) { AppendFloatingPoint(v, out_); });
        break;
      case FieldDescriptor::CPPTYPE_FLOAT:
        WriteEach<float>([&](float v) { AppendFloatingPoint(v, out_); });
        break;
      case FieldDescriptor::CPPTYPE_BOOL:
        WriteEach<bool>([&](bool v) { out_ += v ? "true" : "false"; });
        break;
      case FieldDescriptor::CPPTYPE_ENUM:
        WriteEach<int32_t>([&](int32_t v) { AppendEnum(field_, v, out_); });
        break;
      case FieldDescriptor::CPPTYPE_STRING:
        WriteEach<std::string>([&](const std::string& v) { AppendText(v); });
        break;
      case FieldDescriptor::CPPTYPE_MESSAGE: {
        const int size = reflection_.FieldSize(message_, &field_);
        for (int i = 0; i < size; ++i) {
          if (i > 0) out_ += ',';
          if (absl::Status status = AppendMessageJson(
                  reflection_.GetRepeatedMessage(message_, &field_, i), out_);
              !status.ok()) {
            return status;
          }
        }
        break;
      }
    }
    out_ += ']';
    return absl::OkStatus();
  }

 private:
  // WriteEach appends the elements of the field, of C++ type T, separated
  // by commas; enums are read as their numbers.
  template <typename T, typename Append>
  void WriteEach(Append append) {
    const google::protobuf::RepeatedFieldRef<T> values =
        reflection_.GetRepeatedFieldRef<T>(message_, &field_);
    // Room for the numbers, so the string does not grow by doubling.
    if constexpr (std::is_arithmetic_v<T>) {
      out_.reserve(out_.size() +
                   static_cast<size_t>(values.size()) * (kMaxNumberChars / 2));
    }
    bool first = true;
    for (const auto& value : values) {
      if (!first) out_ += ',';
      first = false;
      append(value);
    }
  }

  void AppendText(const std::string& value) {
    if (field_.type() == FieldDescriptor::TYPE_BYTES) {
      out_ += '"';
      out_ += absl::Base64Escape(value);
      out_ += '"';
    } else {
      AppendJsonString(value, out_);
    }
  }

  const Message& message_;
  const Reflection& reflection_;
  const FieldDescriptor& field_;
  std::string& out_;
};

}  // namespace

absl::Status AppendMessageJson(const Message& message, std::string& out) {
  const Descriptor& type = *message.GetDescriptor();
  if (HandledByProtobuf(type)) {
    std::string json;
    const auto status =
        google::protobuf::util::MessageToJsonString(message, &json);
    if (!status.ok()) {
      return absl::InternalError(
          absl::StrCat("cannot write ", type.full_name(),
                       " as JSON: ", std::string(status.message())));
    }
    out += json;
    return absl::OkStatus();
  }
  std::vector<const FieldDescriptor*> fields;
  message.GetReflection()->ListFields(message, &fields);
  out += '{';
  bool first = true;
  for (const FieldDescriptor* field : fields) {
    if (!first) out += ',';
    first = false;
    AppendJsonString(field->json_name(), out);
    out += ':';
    FieldWriter writer(message, *field, out);
    const absl::Status status =
        field->is_repeated() ? writer.WriteRepeated() : writer.WriteSingular();
    if (!status.ok()) return status;
  }
  out += '}';
  return absl::OkStatus();
}

absl::StatusOr<std::string> MessageJson(const Message& message) {
  std::string json;
  if (absl::Status status = AppendMessageJson(message, json); !status.ok()) {
    return status;
  }
  return json;
}

void AppendJsonString(absl::string_view text, std::string& out) {
  constexpr char kHex[] = "0123456789abcdef";
  out += '"';
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    switch (c) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\r':
        out += "\\r";
        break;
      case '\t':
        out += "\\t";
        break;
      default:
        if (byte < 0x20) {
          out += "\\u00";
          out += kHex[byte >> 4];
          out += kHex[byte & 0xf];
        } else {
          out += c;
        }
    }
  }
  out += '"';
}

}  // namespace freeform::server
