// extension.ts's control flow, with VS Code and the language client replaced by recording fakes (there is no VS Code
// to run it in here): which documents become RRF G-code, when the server starts and with what command line and
// initializationOptions, what a settings change sends, the missing-binary message, and the restart command.
import * as assert from "node:assert/strict";
import * as fs from "node:fs";
import * as os from "node:os";
import * as path from "node:path";
import { test } from "node:test";
// eslint-disable-next-line @typescript-eslint/no-var-requires
const Module = require("node:module") as { _load: (request: string, ...rest: unknown[]) => unknown };

type Listener = (arg: unknown) => unknown;
const log: { clients: FakeClient[]; languageSet: string[]; errors: string[][]; notifications: unknown[][] } = {
  clients: [],
  languageSet: [],
  errors: [],
  notifications: [],
};
const settings: Record<string, unknown> = {};
const listeners: Record<string, Listener[]> = { config: [], open: [] };
const commands: Record<string, () => Promise<void>> = {};

class FakeClient {
  running = false;
  constructor(
    readonly id: string,
    readonly name: string,
    readonly server: { command: string; args: string[] },
    readonly options: { initializationOptions: unknown; documentSelector: unknown },
  ) {
    log.clients.push(this);
  }
  async start(): Promise<void> {
    await new Promise((resolve) => setTimeout(resolve, 5)); // a start takes a while: concurrent opens overlap it
    this.running = true;
  }
  async stop(): Promise<void> {
    this.running = false;
  }
  async sendNotification(type: unknown, params: unknown): Promise<void> {
    log.notifications.push([type, params]);
  }
}

const disposable = { dispose: () => undefined };
const fakeVscode = {
  workspace: {
    getConfiguration: () => ({ get: (key: string, fallback?: unknown) => settings[key] ?? fallback }),
    workspaceFolders: undefined,
    textDocuments: [] as unknown[],
    onDidChangeConfiguration: (f: Listener) => (listeners.config.push(f), disposable),
    onDidOpenTextDocument: (f: Listener) => (listeners.open.push(f), disposable),
  },
  window: {
    createOutputChannel: () => ({ appendLine: () => undefined, dispose: () => undefined }),
    showErrorMessage: async (...args: string[]) => (log.errors.push(args), undefined),
  },
  commands: {
    registerCommand: (id: string, f: () => Promise<void>) => ((commands[id] = f), disposable),
    executeCommand: async () => undefined,
  },
  languages: {
    setTextDocumentLanguage: async (doc: { uri: { fsPath: string } }, id: string) => {
      log.languageSet.push(`${doc.uri.fsPath} ${id}`);
    },
  },
};
const notificationType = { method: "workspace/didChangeConfiguration" };
const loadModule = Module._load;
Module._load = function (request: string, ...rest: unknown[]) {
  if (request === "vscode") {
    return fakeVscode;
  }
  if (request === "vscode-languageclient/node") {
    return { LanguageClient: FakeClient, DidChangeConfigurationNotification: { type: notificationType } };
  }
  return loadModule.call(this, request, ...rest);
};
// eslint-disable-next-line @typescript-eslint/no-var-requires
const extension = require("../extension") as typeof import("../extension");

function doc(file: string, languageId: string): unknown {
  return { uri: { scheme: "file", fsPath: file }, languageId };
}

async function fire(kind: string, arg: unknown): Promise<void> {
  if (kind === "open") {
    fakeVscode.workspace.textDocuments.push(arg);
  }
  await Promise.all(listeners[kind].map((f) => f(arg)));
}

function changed(...keys: string[]): unknown {
  return { affectsConfiguration: (s: string) => keys.includes(s) };
}

const bin = fs.mkdtempSync(path.join(os.tmpdir(), "rrflint-vscode-bin-"));
const rrflint = path.join(bin, "rrflint");
fs.writeFileSync(rrflint, "#!/bin/sh\n");
fs.chmodSync(rrflint, 0o755);
process.env.PATH = bin;

test("the extension, in a fake VS Code", { skip: process.platform === "win32" }, async (t) => {
  await extension.activate({ subscriptions: [] } as never);
  assert.equal(log.clients.length, 0, "nothing starts before an RRF G-code document is open");

  await t.test("extensionless macros opened as plain text become RRF G-code", async () => {
    await fire("open", doc("/card/macros/Park", "plaintext"));
    await fire("open", doc("/card/macros/README.md", "markdown"));
    await fire("open", doc("/card/macros/notes.txt", "plaintext"));
    assert.deepEqual(log.languageSet, ["/card/macros/Park rrf-gcode"]);
    assert.equal(log.clients.length, 0);
  });

  await t.test("an RRF G-code document starts one server, with the settings", async () => {
    settings.firmware = "3.5";
    settings.ignore = ["RRF304"];
    const config = doc("/card/sys/config.g", "rrf-gcode");
    await Promise.all([fire("open", config), fire("open", doc("/card/sys/homeall.g", "rrf-gcode"))]);
    assert.equal(log.clients.length, 1);
    const c = log.clients[0];
    assert.deepEqual(c.server, { command: rrflint, args: ["server"] });
    assert.deepEqual(c.options.initializationOptions, { firmware: "3.5", ignore: ["RRF304"] });
    assert.deepEqual(c.options.documentSelector, [{ scheme: "file", language: "rrf-gcode" }]);
    assert.ok(c.running);
  });

  await t.test("a settings change is sent as didChangeConfiguration; other settings send nothing", async () => {
    settings.firmware = "3.4";
    await fire("config", changed("rrflint.firmware"));
    await fire("config", changed("editor.fontSize"));
    const sent = { settings: { rrflint: { firmware: "3.4", ignore: ["RRF304"] } } };
    assert.deepEqual(log.notifications, [[notificationType, sent]]);
  });

  await t.test("a change of rrflint.path restarts the server", async () => {
    await fire("config", changed("rrflint.path"));
    assert.equal(log.clients.length, 2);
    assert.ok(!log.clients[0].running && log.clients[1].running);
  });

  await t.test("no binary: one error naming rrflint.path, again after Restart server", async () => {
    settings.path = path.join(bin, "absent");
    await fire("config", changed("rrflint.path"));
    await fire("open", doc("/card/sys/homeall.g", "rrf-gcode"));
    assert.equal(log.clients.length, 2, "no client without a binary");
    assert.equal(log.errors.length, 1, JSON.stringify(log.errors));
    assert.match(log.errors[0][0], /rrflint\.path is set to .*absent/);
    assert.equal(log.errors[0][1], "Open Settings");
    await commands["rrflint.restartServer"]();
    assert.equal(log.errors.length, 2);
    // Setting a path that works starts the server, although none ran.
    settings.path = rrflint;
    await fire("config", changed("rrflint.path"));
    assert.equal(log.clients.length, 3);
    assert.ok(log.clients[2].running);
    assert.equal(log.errors.length, 2);
  });

  await extension.deactivate();
  assert.ok(!log.clients[2].running, "deactivate stops the server");
});
