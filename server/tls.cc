#include "tls.h"

#include <grpc/grpc_security_constants.h>
#include <grpcpp/security/auth_context.h>
#include <grpcpp/security/auth_metadata_processor.h>
#include <openssl/bio.h>
#include <openssl/err.h>
#include <openssl/evp.h>
#include <openssl/pem.h>
#include <openssl/x509.h>

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "absl/algorithm/container.h"
#include "absl/strings/ascii.h"
#include "absl/strings/escaping.h"
#include "absl/strings/match.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "freeform/core/status_macros.h"
#include "freeform/io/file.h"
#include "grpc_handoff.h"
#include "spdlog/spdlog.h"

namespace freeform::server {
namespace {

constexpr char kCertFlag[] = "--tls_cert";
constexpr char kKeyFlag[] = "--tls_key";
constexpr char kClientCaFlag[] = "--tls_client_ca";
constexpr char kAllowedClientsFlag[] = "--tls_allowed_clients";

// CheckComplete refuses a TLS option set without what it needs: serving
// plaintext, or any client with a CA-signed certificate, in its place
// would fail open.
absl::Status CheckComplete(const TlsOptions& tls) {
  const bool cert = !tls.cert_file.empty();
  const bool key = !tls.key_file.empty();
  if (cert != key) {
    return absl::InvalidArgumentError(absl::StrCat(
        cert ? kCertFlag : kKeyFlag, " is set without ",
        cert ? kKeyFlag : kCertFlag,
        ": TLS needs both, and freeformd does not fall back to plaintext"));
  }
  if (!tls.client_ca_file.empty() && !cert) {
    return absl::InvalidArgumentError(absl::StrCat(
        kClientCaFlag, " needs ", kCertFlag, " and ", kKeyFlag,
        ": client certificates are checked only over TLS, and freeformd "
        "does not fall back to plaintext"));
  }
  if (!tls.allowed_clients.empty() && tls.client_ca_file.empty()) {
    return absl::InvalidArgumentError(absl::StrCat(
        kAllowedClientsFlag, " needs ", kClientCaFlag, " (with ", kCertFlag,
        " and ", kKeyFlag,
        "): the identities are those of client certificates that CA "
        "signed"));
  }
  for (size_t i = 0; i < tls.allowed_clients.size(); ++i) {
    const std::string& entry = tls.allowed_clients[i];
    if (entry.empty() || entry != absl::StripAsciiWhitespace(entry)) {
      return absl::InvalidArgumentError(absl::StrCat(
          kAllowedClientsFlag, "[", i, "] (\"", absl::CHexEscape(entry),
          "\") is empty or starts or ends with white space"));
    }
  }
  return absl::OkStatus();
}

// ReadTlsFile reads the file of `flag`, its errors prefixed with the flag.
absl::StatusOr<std::string> ReadTlsFile(const char* flag,
                                        const std::string& path) {
  absl::StatusOr<std::string> contents =
      ReadRegularFile(path, kMaxCredentialFileBytes);
  if (!contents.ok()) {
    return absl::Status(contents.status().code(),
                        absl::StrCat(flag, ": ", contents.status().message()));
  }
  return contents;
}

// OpenSSL's objects, each freed with its own function.
struct BioFree {
  void operator()(BIO* bio) const { BIO_free(bio); }
};
struct X509Free {
  void operator()(X509* certificate) const { X509_free(certificate); }
};
struct KeyFree {
  void operator()(EVP_PKEY* key) const { EVP_PKEY_free(key); }
};
using Certificate = std::unique_ptr<X509, X509Free>;
using PrivateKey = std::unique_ptr<EVP_PKEY, KeyFree>;

// Empties OpenSSL's error queue of this thread on entering a check (its
// last error is the check's) and on leaving it: a failed parse here must
// leave nothing for gRPC's own use of OpenSSL.
struct ClearOpenSslErrors {
  ClearOpenSslErrors() { ERR_clear_error(); }
  ~ClearOpenSslErrors() { ERR_clear_error(); }
  ClearOpenSslErrors(const ClearOpenSslErrors&) = delete;
  ClearOpenSslErrors& operator=(const ClearOpenSslErrors&) = delete;
};

// MemoryBio reads `pem`, which ReadTlsFile kept below 1 MiB (an int).
std::unique_ptr<BIO, BioFree> MemoryBio(const std::string& pem) {
  return std::unique_ptr<BIO, BioFree>(
      BIO_new_mem_buf(pem.data(), static_cast<int>(pem.size())));
}

// NoPassphrase answers OpenSSL's request for the passphrase of an
// encrypted key: freeformd has none, so reading the key fails at once
// instead of prompting on the terminal.
int NoPassphrase(char* /*buffer*/, int /*size*/, int /*writing*/,
                 void* /*data*/) {
  return -1;
}

// FirstCertificate returns the first certificate of the PEM file of `flag`
// (the server's own, for the certificate file), after checking that every
// certificate block of the file parses, as gRPC will read them all. Like
// gRPC (and OpenSSL's PEM reader), it skips text outside the blocks and
// blocks of other types.
absl::StatusOr<Certificate> FirstCertificate(const char* flag,
                                             const std::string& path,
                                             const std::string& pem) {
  const ClearOpenSslErrors clear;
  const std::unique_ptr<BIO, BioFree> bio = MemoryBio(pem);
  if (bio == nullptr) return absl::ResourceExhaustedError("out of memory");
  Certificate first;
  int count = 0;
  while (Certificate next = Certificate(
             PEM_read_bio_X509(bio.get(), nullptr, NoPassphrase, nullptr))) {
    if (count++ == 0) first = std::move(next);
  }
  // The loop ends at the end of the data (no further certificate block)
  // or at a certificate block that does not parse.
  const unsigned long error = ERR_peek_last_error();
  const bool clean_end = ERR_GET_LIB(error) == ERR_LIB_PEM &&
                         ERR_GET_REASON(error) == PEM_R_NO_START_LINE;
  if (count == 0) {
    return absl::InvalidArgumentError(
        absl::StrCat(flag, "=", path, " holds no PEM certificate"));
  }
  if (!clean_end) {
    return absl::InvalidArgumentError(
        absl::StrCat(flag, "=", path,
                     " holds a PEM certificate block after "
                     "certificate ",
                     count, " that does not parse"));
  }
  return first;
}

// CheckKeyMatches checks that the key file holds an unencrypted PEM
// private key, the key of the first certificate of the certificate file.
absl::Status CheckKeyMatches(const TlsOptions& tls, const std::string& key_pem,
                             const X509& certificate) {
  const ClearOpenSslErrors clear;
  const std::unique_ptr<BIO, BioFree> bio = MemoryBio(key_pem);
  if (bio == nullptr) return absl::ResourceExhaustedError("out of memory");
  const PrivateKey key(
      PEM_read_bio_PrivateKey(bio.get(), nullptr, NoPassphrase, nullptr));
  if (key == nullptr) {
    return absl::InvalidArgumentError(absl::StrCat(
        kKeyFlag, "=", tls.key_file,
        " holds no PEM private key (or an encrypted one: freeformd takes no "
        "passphrase)"));
  }
  if (X509_check_private_key(&certificate, key.get()) != 1) {
    return absl::InvalidArgumentError(
        absl::StrCat("the private key in ", kKeyFlag, "=", tls.key_file,
                     " does not match the certificate in ", kCertFlag, "=",
                     tls.cert_file, " (the first of its chain)"));
  }
  return absl::OkStatus();
}

// The identities of a client certificate that the allowed entries are
// compared with, as gRPC read them from the certificate (AuthContext).
struct ClientIdentities {
  std::vector<std::string> dns_names;
  std::vector<std::string> uris;
  std::vector<std::string> common_names;
};

std::vector<std::string> PropertyValues(const grpc::AuthContext& context,
                                        const char* name) {
  std::vector<std::string> values;
  for (const grpc::string_ref& value : context.FindPropertyValues(name)) {
    values.emplace_back(value.data(), value.size());
  }
  return values;
}

ClientIdentities IdentitiesOf(const grpc::AuthContext& context) {
  return {.dns_names = PropertyValues(context, GRPC_PEER_DNS_PROPERTY_NAME),
          .uris = PropertyValues(context, GRPC_PEER_URI_PROPERTY_NAME),
          .common_names = PropertyValues(context, GRPC_X509_CN_PROPERTY_NAME)};
}

// Describe lists the identities for the log, each escaped (a certificate's
// names may hold any byte).
std::string Describe(const ClientIdentities& identities) {
  const auto escaped = [](std::string* out, const std::string& value) {
    absl::StrAppend(out, absl::CHexEscape(value));
  };
  return absl::StrCat(
      "CN=[", absl::StrJoin(identities.common_names, ",", escaped), "] DNS=[",
      absl::StrJoin(identities.dns_names, ",", escaped), "] URI=[",
      absl::StrJoin(identities.uris, ",", escaped), "]");
}

// ClientAllowList lets a call through when its client certificate carries
// one of the allowed identities (TlsOptions::allowed_clients), and answers
// any other PERMISSION_DENIED: the certificate authenticated the client
// (the CA signed it), but that identity may not use the service. gRPC asks
// it before every call of the listener, health and reflection included,
// before any interceptor or handler sees the call.
class ClientAllowList final : public grpc::AuthMetadataProcessor {
 public:
  explicit ClientAllowList(std::vector<std::string> allowed)
      : allowed_(std::move(allowed)) {
    HandOffToGrpc(this);  // to every Process, on gRPC's threads
  }

  // Process only compares a few strings: gRPC runs it on the call's own
  // thread instead of a thread pool of its own.
  bool IsBlocking() const override { return false; }

  grpc::Status Process(const InputMetadata& metadata,
                       grpc::AuthContext* context, OutputMetadata* /*consumed*/,
                       OutputMetadata* /*response*/) override {
    TakeBackFromGrpc(this);
    const ClientIdentities identities =
        context == nullptr ? ClientIdentities{} : IdentitiesOf(*context);
    if (Allows(identities)) return grpc::Status::OK;
    const auto path = metadata.find(":path");
    spdlog::warn(
        "refused a call to {}: client certificate {} is not in "
        "--tls_allowed_clients (PERMISSION_DENIED)",
        path == metadata.end() ? std::string("(unknown method)")
                               : absl::CHexEscape(absl::string_view(
                                     path->second.data(), path->second.size())),
        Describe(identities));
    return grpc::Status(grpc::StatusCode::PERMISSION_DENIED,
                        "the client certificate's identity is not one of the "
                        "server's --tls_allowed_clients");
  }

 private:
  bool Allows(const ClientIdentities& identities) const {
    return absl::c_any_of(allowed_, [&](const std::string& entry) {
      return absl::c_any_of(identities.dns_names,
                            [&](const std::string& name) {
                              return absl::EqualsIgnoreCase(name, entry);
                            }) ||
             absl::c_linear_search(identities.uris, entry) ||
             absl::c_linear_search(identities.common_names, entry);
    });
  }

  const std::vector<std::string> allowed_;
};

}  // namespace

absl::StatusOr<std::shared_ptr<grpc::ServerCredentials>> ListenerCredentials(
    const TlsOptions& tls) {
  RETURN_IF_ERROR(CheckComplete(tls));
  if (tls.cert_file.empty()) return grpc::InsecureServerCredentials();
  absl::StatusOr<std::string> cert = ReadTlsFile(kCertFlag, tls.cert_file);
  if (!cert.ok()) return cert.status();
  absl::StatusOr<std::string> key = ReadTlsFile(kKeyFlag, tls.key_file);
  if (!key.ok()) return key.status();
  absl::StatusOr<Certificate> leaf =
      FirstCertificate(kCertFlag, tls.cert_file, *cert);
  if (!leaf.ok()) return leaf.status();
  RETURN_IF_ERROR(CheckKeyMatches(tls, *key, **leaf));
  grpc::SslServerCredentialsOptions options;
  options.pem_key_cert_pairs.push_back({*std::move(key), *std::move(cert)});
  if (!tls.client_ca_file.empty()) {
    absl::StatusOr<std::string> ca =
        ReadTlsFile(kClientCaFlag, tls.client_ca_file);
    if (!ca.ok()) return ca.status();
    absl::StatusOr<Certificate> first_ca =
        FirstCertificate(kClientCaFlag, tls.client_ca_file, *ca);
    if (!first_ca.ok()) return first_ca.status();
    options.pem_root_certs = *std::move(ca);
    options.client_certificate_request =
        GRPC_SSL_REQUEST_AND_REQUIRE_CLIENT_CERTIFICATE_AND_VERIFY;
  }
  std::shared_ptr<grpc::ServerCredentials> credentials =
      grpc::SslServerCredentials(options);
  if (!tls.allowed_clients.empty()) {
    credentials->SetAuthMetadataProcessor(
        std::make_shared<ClientAllowList>(tls.allowed_clients));
  }
  return credentials;
}

}  // namespace freeform::server
