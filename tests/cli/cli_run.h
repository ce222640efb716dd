// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Runs sonargrid-cli (or a shell) as a script would and keeps what it printed: the process runner
// the CLI tests share. SONARGRID_CLI is the binary's path (tests/cli/CMakeLists.txt).

#include <QByteArray>
#include <QProcess>
#include <QProcessEnvironment>
#include <QString>
#include <QStringList>

namespace cli_test {

inline const QString kCli = QStringLiteral(SONARGRID_CLI);

struct Run {
  bool finished = false;
  QProcess::ExitStatus status = QProcess::CrashExit;
  int code = -1;
  QByteArray out;
  QByteArray err;
};

// Runs `program` with `args` in `workDir` (the test's own when empty) and `environment` (the
// test's own when empty); never waits more than `timeoutMs`.
inline Run runProgram(const QString& program, const QStringList& args, const QString& workDir = {},
                      const QProcessEnvironment& environment = {}, int timeoutMs = 120000) {
  QProcess p;
  p.setProgram(program);
  p.setArguments(args);
  if (!workDir.isEmpty()) p.setWorkingDirectory(workDir);
  if (!environment.isEmpty()) p.setProcessEnvironment(environment);
  p.start();
  Run r;
  if (!p.waitForStarted(10000)) {
    r.err = "did not start: " + p.errorString().toUtf8();
    return r;
  }
  r.finished = p.waitForFinished(timeoutMs);
  if (!r.finished) {
    p.kill();
    p.waitForFinished(5000);
    r.err = "timed out after " + QByteArray::number(timeoutMs / 1000) + " s";
    return r;
  }
  r.status = p.exitStatus();
  r.code = p.exitCode();
  r.out = p.readAllStandardOutput();
  r.err = p.readAllStandardError();
  return r;
}

inline Run runCli(const QStringList& args, const QString& workDir = {}) {
  return runProgram(kCli, args, workDir);
}

// The command, its exit status and the start of what it printed, for a failure message.
inline QByteArray describe(const QStringList& args, const Run& r) {
  return "sonargrid-cli " + args.join(' ').toUtf8() + "\n  exit " + QByteArray::number(r.code) +
         (r.status == QProcess::CrashExit ? " (crashed)" : "") + "\n  stdout: " + r.out.left(600) +
         "\n  stderr: " + r.err.left(600);
}

}  // namespace cli_test
