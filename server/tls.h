// TLS of freeformd's listener: the options (--tls_cert, --tls_key,
// --tls_client_ca, --tls_allowed_clients), checked when the server starts,
// and the allow-list of client identities every call passes before gRPC
// hands it to a service.
//
// The configuration fails closed: any TLS option set without what it needs
// refuses to start, never serves plaintext. Each file is read once, as a
// regular file of at most kMaxCredentialFileBytes (freeform/io/file.h);
// the private key must match the certificate; the CA must hold a
// certificate. docs/operations.md states the rules and the identity
// matching. Thread-safe.
#ifndef FREEFORM_SERVER_TLS_H_
#define FREEFORM_SERVER_TLS_H_

#include <grpcpp/security/server_credentials.h>

#include <memory>
#include <string>
#include <vector>

#include "absl/status/statusor.h"

namespace freeform::server {

struct TlsOptions {
  // PEM files; TLS is on when cert and key are both set, and one without
  // the other refuses to start.
  std::string cert_file;
  std::string key_file;
  // With a client CA, clients must present a certificate it signed (mTLS).
  // Needs cert and key.
  std::string client_ca_file;
  // With entries, a client certificate must also carry one of these
  // identities: a DNS name (compared ignoring ASCII case) or a URI (exactly,
  // e.g. a SPIFFE ID) of its subject alternative names, or its subject's
  // common name (exactly). No wildcards. Needs the client CA. Calls from
  // any other certificate get PERMISSION_DENIED and a warning in the log.
  std::vector<std::string> allowed_clients;
};

// ListenerCredentials returns the credentials of the listener: plaintext
// when no TLS option is set, TLS (and mTLS with a client CA, restricted to
// the allowed clients when listed) otherwise. INVALID_ARGUMENT naming the
// flags when an option lacks what it needs or a file's contents do not
// serve (no PEM certificate, no unencrypted PEM key, a key that does not
// match the certificate); NOT_FOUND or FAILED_PRECONDITION naming the flag
// and the file when one cannot be read.
absl::StatusOr<std::shared_ptr<grpc::ServerCredentials>> ListenerCredentials(
    const TlsOptions& tls);

}  // namespace freeform::server

#endif  // FREEFORM_SERVER_TLS_H_
