// The server command line the extension starts, against the real binary: found on PATH as the extension finds it,
// spoken to with vscode-jsonrpc (the transport vscode-languageclient uses), with the extension's
// initializationOptions and didChangeConfiguration. Needs RRFLINT = the built rrflint binary; skipped without it.
import * as assert from "node:assert/strict";
import * as cp from "node:child_process";
import * as fs from "node:fs";
import * as os from "node:os";
import * as path from "node:path";
import { pathToFileURL } from "node:url";
import { test } from "node:test";
import * as rpc from "vscode-jsonrpc/node";
import { didChangeConfigurationParams, resolveBinary, serverArgs, serverSettings } from "../server";

const binary = process.env.RRFLINT;

interface Diagnostic {
  code?: string | number;
  range: { start: { line: number; character: number } };
}

test("rrflint server answers initialize, publishes diagnostics, and shuts down", { skip: !binary }, async () => {
  const found = resolveBinary("", undefined, { PATH: path.dirname(path.resolve(binary ?? "")) });
  assert.ok(found.ok, found.ok ? "" : found.message);
  const server = cp.spawn(found.path, serverArgs(), { stdio: ["pipe", "pipe", "inherit"] });
  const exited = new Promise<number | null>((resolve) => server.on("exit", resolve));
  const connection = rpc.createMessageConnection(
    new rpc.StreamMessageReader(server.stdout),
    new rpc.StreamMessageWriter(server.stdin),
  );
  const card = fs.mkdtempSync(path.join(os.tmpdir(), "rrflint-vscode-card-"));
  fs.mkdirSync(path.join(card, "sys"));
  const config = path.join(card, "sys", "config.g");
  const text = "; tool 1 is named before M563 creates it\nG10 P1 X0 Y0 Z0\n";
  fs.writeFileSync(config, text);
  const uri = pathToFileURL(config).href;
  const diagnostics = new Promise<Diagnostic[]>((resolve) => {
    connection.onNotification("textDocument/publishDiagnostics", (p: { uri: string; diagnostics: Diagnostic[] }) => {
      if (p.uri === uri) {
        resolve(p.diagnostics);
      }
    });
  });
  connection.listen();
  try {
    const init = await connection.sendRequest<{ capabilities: Record<string, unknown> }>("initialize", {
      processId: process.pid,
      rootUri: pathToFileURL(card).href,
      capabilities: {},
      initializationOptions: serverSettings({ firmware: "3.5", select: [], ignore: [] }),
    });
    assert.ok(init.capabilities.textDocumentSync !== undefined, JSON.stringify(init));
    await connection.sendNotification("initialized", {});
    await connection.sendNotification("workspace/didChangeConfiguration", didChangeConfigurationParams({}));
    await connection.sendNotification("textDocument/didOpen", {
      textDocument: { uri, languageId: "rrf-gcode", version: 1, text },
    });
    const found301 = (await diagnostics).find((d) => d.code === "RRF301");
    assert.ok(found301, "RRF301 (tool used before M563) is published for config.g");
    assert.equal(found301.range.start.line, 1);
    assert.equal(await connection.sendRequest("shutdown"), null);
    await connection.sendNotification("exit");
    assert.equal(await exited, 0);
  } finally {
    connection.dispose();
    server.kill();
    fs.rmSync(card, { recursive: true, force: true });
  }
});
