// SPDX-License-Identifier: GPL-3.0-or-later
// The console examples of docs/cli.md are real runs (issue 17): every fenced block whose first line
// starts with "$ " is replayed, command by command, by /bin/sh in a fresh folder that holds the
// repository's datasets/ and tests/ (the examples run "from the repository root") and finds
// sonargrid-cli on its PATH; what each command prints (stdout and stderr) must be the lines the
// block shows under it. Times (`"elapsed_ms":…`, "… ms") are compared as "a number".
//
// A block preceded by a line `<!-- not replayed: REASON -->` is skipped (an abbreviated listing,
// a live robot). Blocks between `<!-- BEGIN GENERATED` markers are docs_models_in_sync's
// (check_generated_doc.cmake), not this test's.
//
// To rewrite the examples from real runs: SONARGRID_UPDATE_DOCS=1 ctest -R tst_cli_docs (or run
// the binary with that variable); then review the diff of docs/cli.md.

#include <QDir>
#include <QFile>
#include <QProcess>
#include <QRegularExpression>
#include <QSaveFile>
#include <QTemporaryDir>
#include <QtTest>

#include "cli_run.h"

namespace {

const QString kSource = QStringLiteral(SONARGRID_SOURCE_DIR);
const QString kDoc = kSource + "/docs/cli.md";
const QByteArray kEnd = "@@sonargrid-docs-end@@\n";

// One command of a block: its lines as the document shows them ("$ …" and continuations) and the
// output shown under it.
struct Command {
  QStringList lines;
  QString output;
};

struct Block {
  int firstLine = 0;                 // 1-based line of the opening fence
  int fenceBegin = 0, fenceEnd = 0;  // indexes of the fence lines in the document's lines
  std::vector<Command> commands;
};

QStringList documentLines() {
  QFile f(kDoc);
  if (!f.open(QIODevice::ReadOnly)) qFatal("cannot read %s", qPrintable(kDoc));
  return QString::fromUtf8(f.readAll()).split('\n');
}

// The console blocks of the document, in order.
std::vector<Block> consoleBlocks(const QStringList& lines) {
  std::vector<Block> out;
  for (int i = 0; i < lines.size(); ++i) {
    if (!lines[i].startsWith("```")) continue;
    int end = i + 1;
    while (end < lines.size() && !lines[end].startsWith("```")) ++end;
    if (end >= lines.size()) break;
    const bool console = end > i + 1 && lines[i + 1].startsWith("$ ");
    int previous = i - 1;
    while (previous >= 0 && lines[previous].trimmed().isEmpty()) --previous;
    const bool skipped = previous >= 0 && lines[previous].startsWith("<!-- not replayed:");
    if (console && !skipped) {
      Block b;
      b.firstLine = i + 1;
      b.fenceBegin = i;
      b.fenceEnd = end;
      bool continued = false;
      for (int k = i + 1; k < end; ++k) {
        const QString& l = lines[k];
        if (continued || l.startsWith("$ ")) {
          if (!continued) b.commands.push_back({});
          b.commands.back().lines << l;
          continued = l.endsWith('\\');
        } else {
          b.commands.back().output += l + '\n';
        }
      }
      out.push_back(b);
    }
    i = end;
  }
  return out;
}

// Runs the block's commands in one shell, in a fresh folder; returns each command's output.
QStringList replay(const Block& block, QString* error) {
  QTemporaryDir dir;
  QDir bin(dir.path());
  if (!dir.isValid() || !bin.mkdir("bin") ||
      !QFile::link(cli_test::kCli, dir.filePath("bin/sonargrid-cli")) ||
      !QFile::link(kSource + "/datasets", dir.filePath("datasets")) ||
      !QFile::link(kSource + "/tests", dir.filePath("tests"))) {
    *error = "cannot prepare a folder to run in";
    return {};
  }
  QByteArray script = "exec 2>&1\n";
  for (const Command& c : block.commands) {
    QString command = c.lines.join('\n');
    command.remove(0, 2);  // "$ "
    // The exit status survives the marker, for an `echo $?` that follows.
    script +=
        command.toUtf8() + "\n__status=$?; printf '" + kEnd.trimmed() + "\\n'; (exit $__status)\n";
  }
  QProcessEnvironment env = QProcessEnvironment::systemEnvironment();
  env.insert("PATH", dir.filePath("bin") + ":" + env.value("PATH"));
  env.remove("SONARGRID_THREADS");
  const cli_test::Run r = cli_test::runProgram("/bin/sh", {"-c", script}, dir.path(), env);
  if (!r.finished || r.status != QProcess::NormalExit) {
    *error = "the shell did not finish: " + QString::fromUtf8(r.err);
    return {};
  }
  QStringList outputs;
  QByteArray rest = r.out;
  for (std::size_t k = 0; k < block.commands.size(); ++k) {
    const qsizetype at = rest.indexOf(kEnd);
    if (at < 0) {
      *error = "a command's output has no end marker: " + QString::fromUtf8(r.out);
      return {};
    }
    outputs << QString::fromUtf8(rest.left(at));
    rest = rest.mid(at + kEnd.size());
  }
  return outputs;
}

// Times vary from run to run: any number of milliseconds reads the same.
QString normalised(QString text) {
  static const QRegularExpression elapsed(R"("elapsed_ms":[-+0-9.eE]+)");
  static const QRegularExpression ms(R"([0-9]+(\.[0-9]+)?(e[-+]?[0-9]+)? ms\b)");
  text.replace(elapsed, R"("elapsed_ms":…)");
  text.replace(ms, "… ms");
  return text;
}

bool updating() {
  return qEnvironmentVariable("SONARGRID_UPDATE_DOCS") == "1";
}

}  // namespace

class TstCliDocs : public QObject {
  Q_OBJECT

 private slots:
  void examplesAreRealRuns_data();
  void examplesAreRealRuns();
};

void TstCliDocs::examplesAreRealRuns_data() {
  QTest::addColumn<int>("index");
  const std::vector<Block> blocks = consoleBlocks(documentLines());
  // The sections this project relies on most must stay covered: map, score, compare.
  QVERIFY2(blocks.size() >= 8, "docs/cli.md lost its console examples");
  for (std::size_t k = 0; k < blocks.size(); ++k) {
    QTest::addRow("cli.md:%d %s", blocks[k].firstLine,
                  qPrintable(blocks[k].commands.front().lines.front().left(60)))
        << static_cast<int>(k);
  }
}

void TstCliDocs::examplesAreRealRuns() {
  QFETCH(int, index);
  // Read again: an update of an earlier row may have moved the lines.
  QStringList lines = documentLines();
  const std::vector<Block> blocks = consoleBlocks(lines);
  QVERIFY(static_cast<std::size_t>(index) < blocks.size());
  const Block& block = blocks[static_cast<std::size_t>(index)];
  QString error;
  const QStringList outputs = replay(block, &error);
  QVERIFY2(error.isEmpty(), qPrintable(error));

  if (updating()) {
    QStringList replaced;
    for (std::size_t k = 0; k < block.commands.size(); ++k) {
      replaced << block.commands[k].lines;
      QString out = outputs[static_cast<int>(k)];
      if (out.endsWith('\n')) out.chop(1);
      if (!out.isEmpty()) replaced << out.split('\n');
    }
    lines = lines.mid(0, block.fenceBegin + 1) + replaced + lines.mid(block.fenceEnd);
    QSaveFile f(kDoc);
    QVERIFY(f.open(QIODevice::WriteOnly));
    f.write(lines.join('\n').toUtf8());
    QVERIFY(f.commit());
    return;
  }
  for (std::size_t k = 0; k < block.commands.size(); ++k) {
    const Command& c = block.commands[k];
    const QString expected = normalised(c.output),
                  actual = normalised(outputs[static_cast<int>(k)]);
    QVERIFY2(actual == expected,
             qPrintable(QString("docs/cli.md:%1: `%2` printed\n%3\nbut the document shows\n%4\n"
                                "(SONARGRID_UPDATE_DOCS=1 rewrites the examples from real runs)")
                            .arg(block.firstLine)
                            .arg(c.lines.join(' '))
                            .arg(actual, expected)));
  }
}

QTEST_GUILESS_MAIN(TstCliDocs)
#include "tst_cli_docs.moc"
