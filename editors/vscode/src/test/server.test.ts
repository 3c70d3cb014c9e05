// The binary lookup and the settings sent to the server (no VS Code needed).
import * as assert from "node:assert/strict";
import * as fs from "node:fs";
import * as os from "node:os";
import * as path from "node:path";
import { test } from "node:test";
import { didChangeConfigurationParams, resolveBinary, serverArgs, serverSettings } from "../server";

// Executable bits and #! scripts are POSIX; on Windows the lookup goes by PATHEXT.
const posix = { skip: process.platform === "win32" };

function scratch(): string {
  return fs.mkdtempSync(path.join(os.tmpdir(), "rrflint-vscode-"));
}

function executable(dir: string, name: string, mode = 0o755): string {
  const file = path.join(dir, name);
  fs.writeFileSync(file, "#!/bin/sh\n");
  fs.chmodSync(file, mode);
  return file;
}

test("settings: empty values are left out, so .rrflint.toml or the default applies", () => {
  assert.deepEqual(serverSettings({ firmware: "", select: [], ignore: [] }), {});
  assert.deepEqual(serverSettings({}), {});
  assert.deepEqual(serverSettings({ firmware: " 3.5 ", select: ["RRF3", " "], ignore: ["RRF304"] }), {
    firmware: "3.5",
    select: ["RRF3"],
    ignore: ["RRF304"],
  });
  // Values of the wrong type (a hand-edited settings.json) are dropped rather than sent.
  assert.deepEqual(serverSettings({ firmware: 3.5, select: "RRF3", ignore: [1, "RRF1"] }), { ignore: ["RRF1"] });
});

test("didChangeConfiguration sends {settings: {rrflint: {...}}}", () => {
  assert.deepEqual(didChangeConfigurationParams({ firmware: "3.4" }), { settings: { rrflint: { firmware: "3.4" } } });
});

test("the server command line is `rrflint server`", () => {
  assert.deepEqual(serverArgs(), ["server"]);
});

test("binary: found on PATH, the first executable one wins", posix, () => {
  const a = scratch();
  const b = scratch();
  executable(a, "rrflint", 0o644); // not executable: skipped
  const wanted = executable(b, "rrflint");
  const found = resolveBinary("", undefined, { PATH: [a, "", b].join(path.delimiter) });
  assert.deepEqual(found, { ok: true, path: wanted });
});

test("binary: missing from PATH gives a message that names the setting", () => {
  const found = resolveBinary("", undefined, { PATH: scratch() });
  assert.equal(found.ok, false);
  assert.match(found.ok ? "" : found.message, /not found on PATH.*rrflint\.path/);
  assert.equal(resolveBinary("  ", undefined, {}).ok, false);
});

test("binary: rrflint.path, absolute, relative to the workspace, or from ~", posix, () => {
  const dir = scratch();
  const file = executable(dir, "rrflint-dev");
  assert.deepEqual(resolveBinary(file, undefined, {}), { ok: true, path: file });
  assert.deepEqual(resolveBinary("rrflint-dev", dir, {}), { ok: true, path: file });
  assert.deepEqual(resolveBinary("~/rrflint-dev", undefined, { HOME: dir }), { ok: true, path: file });
});

test("binary: rrflint.path that is missing, a folder or not executable is reported", () => {
  const dir = scratch();
  const notExecutable = executable(dir, "plain", 0o644);
  for (const setting of [path.join(dir, "absent"), dir, notExecutable]) {
    const found = resolveBinary(setting, undefined, {});
    assert.equal(found.ok, false, setting);
    assert.match(found.ok ? "" : found.message, /rrflint\.path is set to .* is not an executable file/);
  }
});
