// The rrflint extension: gives extensionless macros the RRF G-code language, starts `rrflint server` once an RRF
// G-code document is open, tells it the rrflint.* settings, and offers "rrflint: Restart server".
import * as vscode from "vscode";
import { DidChangeConfigurationNotification, LanguageClient, LanguageClientOptions } from "vscode-languageclient/node";
import { isExtensionlessMacro } from "./files";
import { didChangeConfigurationParams, resolveBinary, serverArgs, serverSettings, ServerSettings } from "./server";

const LANGUAGE = "rrf-gcode";
let client: LanguageClient | undefined;
let starting: Promise<void> | undefined;
let output: vscode.OutputChannel;
// The "binary not found" message is shown once, not for every document opened; a restart shows it again.
let reportedMissing = false;

function currentSettings(): ServerSettings {
  const c = vscode.workspace.getConfiguration("rrflint");
  return serverSettings({ firmware: c.get("firmware"), select: c.get("select"), ignore: c.get("ignore") });
}

function errorText(err: unknown): string {
  return err instanceof Error ? err.message : String(err);
}

async function reportMissing(message: string): Promise<void> {
  output.appendLine(message);
  if (reportedMissing) {
    return;
  }
  reportedMissing = true;
  const choice = await vscode.window.showErrorMessage(message, "Open Settings");
  if (choice === "Open Settings") {
    await vscode.commands.executeCommand("workbench.action.openSettings", "rrflint.path");
  }
}

async function launch(): Promise<void> {
  const setting = vscode.workspace.getConfiguration("rrflint").get<string>("path", "");
  const base = vscode.workspace.workspaceFolders?.[0]?.uri.fsPath;
  const binary = resolveBinary(setting, base, process.env);
  if (!binary.ok) {
    // Not awaited: the message stays up until the user answers, and a restart or deactivate must not wait for that.
    void reportMissing(binary.message);
    return;
  }
  output.appendLine(`rrflint: starting ${binary.path} ${serverArgs().join(" ")}`);
  const clientOptions: LanguageClientOptions = {
    documentSelector: [{ scheme: "file", language: LANGUAGE }],
    initializationOptions: currentSettings(),
    outputChannel: output,
  };
  const next = new LanguageClient("rrflint", "rrflint", { command: binary.path, args: serverArgs() }, clientOptions);
  try {
    await next.start();
    client = next;
  } catch (err) {
    const message = `rrflint: could not start '${binary.path} server': ${errorText(err)}`;
    output.appendLine(message);
    void vscode.window.showErrorMessage(message);
  }
}

/** Starts the server unless it runs or is starting. */
function start(): Promise<void> {
  if (client) {
    return Promise.resolve();
  }
  if (!starting) {
    starting = launch().finally(() => (starting = undefined));
  }
  return starting;
}

async function stop(): Promise<void> {
  await starting;
  const running = client;
  client = undefined;
  if (running) {
    try {
      await running.stop();
    } catch (err) {
      output.appendLine(`rrflint: stopping the server failed: ${errorText(err)}`);
    }
  }
}

async function restart(): Promise<void> {
  await stop();
  reportedMissing = false;
  await start();
}

async function onConfigurationChange(event: vscode.ConfigurationChangeEvent): Promise<void> {
  if (event.affectsConfiguration("rrflint.path")) {
    // Also when no server runs because the binary was not found: the new path may be the fix.
    if (client || starting || vscode.workspace.textDocuments.some((d) => d.languageId === LANGUAGE)) {
      await restart();
    }
    return;
  }
  const affected = ["rrflint.firmware", "rrflint.select", "rrflint.ignore"].some((s) => event.affectsConfiguration(s));
  if (client && affected) {
    const params = didChangeConfigurationParams(currentSettings());
    await client.sendNotification(DidChangeConfigurationNotification.type, params);
  }
}

/** Gives an extensionless macro opened as plain text the RRF G-code language; starts the server for G-code. */
async function onOpen(document: vscode.TextDocument): Promise<void> {
  if (document.uri.scheme !== "file") {
    return;
  }
  if (document.languageId === "plaintext" && isExtensionlessMacro(document.uri.fsPath)) {
    // Changing the language reopens the document, which comes back here as rrf-gcode.
    await vscode.languages.setTextDocumentLanguage(document, LANGUAGE);
  } else if (document.languageId === LANGUAGE) {
    await start();
  }
}

export async function activate(context: vscode.ExtensionContext): Promise<void> {
  output = vscode.window.createOutputChannel("rrflint");
  context.subscriptions.push(
    output,
    vscode.commands.registerCommand("rrflint.restartServer", restart),
    vscode.workspace.onDidChangeConfiguration(onConfigurationChange),
    vscode.workspace.onDidOpenTextDocument(onOpen),
  );
  await Promise.all(vscode.workspace.textDocuments.map(onOpen));
}

export function deactivate(): Promise<void> {
  return stop();
}
