// Certificates made by openssl for one test: a CA, a server certificate
// for 127.0.0.1 and localhost, a client certificate (CN=client), and any
// further client certificates a test asks for, all signed by the CA, with
// P-256 keys (a tenth of RSA's time to make), in a temporary directory
// removed at the end. TlsClientOptions makes a client
// that trusts the CA.
#ifndef FREEFORM_TESTS_INTEGRATION_TLS_CERTIFICATES_H_
#define FREEFORM_TESTS_INTEGRATION_TLS_CERTIFICATES_H_

#include <stdlib.h>

#include <chrono>
#include <string>

#include "absl/strings/str_cat.h"
#include "cli_test_util.h"
#include "freeform/client.h"

namespace freeform {

class Certificates {
 public:
  Certificates() {
    char pattern[] = "/tmp/freeform_tls_XXXXXX";
    directory_ = mkdtemp(pattern);
    ok_ = Run(absl::StrCat(
              "openssl req -x509 -newkey ec -pkeyopt "
              "ec_paramgen_curve:prime256v1 -nodes -days 2 "
              "-subj /CN=test-ca -keyout ca.key -out ca.pem && ",
              Signed("server", "localhost", "IP:127.0.0.1,DNS:localhost"))) &&
          AddClient("client", "client");
  }
  ~Certificates() { RunCommand(absl::StrCat("rm -rf ", directory_)); }
  Certificates(const Certificates&) = delete;
  Certificates& operator=(const Certificates&) = delete;

  bool ok() const { return ok_; }
  std::string Path(const std::string& name) const {
    return absl::StrCat(directory_, "/", name);
  }

  // AddClient makes NAME.pem and NAME.key: a client certificate the CA
  // signs with subject CN=`common_name` and, unless empty, the subject
  // alternative names `alt_names` (openssl's form: "DNS:a.example,URI:
  // spiffe://example/a"). Returns whether openssl succeeded.
  bool AddClient(const std::string& name, const std::string& common_name,
                 const std::string& alt_names = "") {
    return Run(Signed(name, common_name, alt_names));
  }

 private:
  // The shell commands that make NAME.key and NAME.pem, signed by the CA.
  static std::string Signed(const std::string& name,
                            const std::string& common_name,
                            const std::string& alt_names) {
    const std::string write_extensions =
        alt_names.empty() ? std::string()
                          : absl::StrCat("printf 'subjectAltName=", alt_names,
                                         "' > ", name, ".ext && ");
    const std::string extensions =
        alt_names.empty() ? std::string()
                          : absl::StrCat(" -extfile ", name, ".ext");
    return absl::StrCat(
        write_extensions,
        "openssl req -newkey ec -pkeyopt ec_paramgen_curve:prime256v1 -nodes "
        "-subj '/CN=",
        common_name, "' -keyout ", name, ".key -out ", name, ".csr && ",
        "openssl x509 -req -in ", name, ".csr -CA ca.pem -CAkey ca.key ",
        "-CAcreateserial -days 2", extensions, " -out ", name, ".pem");
  }

  bool Run(const std::string& commands) const {
    const CommandResult result = RunCommand(
        absl::StrCat("(cd ", directory_, " && set -e && ", commands, ")"));
    EXPECT_EQ(result.exit_code, 0) << result.output;
    return result.exit_code == 0;
  }

  std::string directory_;
  bool ok_ = false;
};

// TlsClientOptions returns the options of a TLS client of 127.0.0.1:PORT
// that trusts the test CA; with `client` (a name given to AddClient, or
// "client") it presents that certificate.
inline ClientOptions TlsClientOptions(const Certificates& certificates,
                                      int port,
                                      const std::string& client = "") {
  ClientOptions options;
  options.target = absl::StrCat("127.0.0.1:", port);
  options.timeout = std::chrono::seconds(10);
  options.use_tls = true;
  options.root_ca_file = certificates.Path("ca.pem");
  if (!client.empty()) {
    options.cert_file = certificates.Path(client + ".pem");
    options.key_file = certificates.Path(client + ".key");
  }
  return options;
}

}  // namespace freeform

#endif  // FREEFORM_TESTS_INTEGRATION_TLS_CERTIFICATES_H_
