// The Run panel: start / pause / resume / stop, the run's budgets, threads and seed, and where it
// stands (generation, best fitness, simulations/s, elapsed, ETA). Also opens or resumes a run
// directory written by `bhm evolve`.
#include <cstdio>
#include <string>

#include <imgui.h>

#include "app/gui/actions/draft_edits.hpp"
#include "app/gui/actions/studio_actions.hpp"
#include "app/gui/panels/file_dialog_widget.hpp"
#include "app/gui/panels/panels.hpp"
#include "app/gui/settings/studio_paths.hpp"
#include "app/gui/widgets/ui_widgets.hpp"

namespace bhm::app::gui {

namespace {

void controls(Studio& s) {
    const RunPhase phase = s.run.evolution.phase();
    const bool live = run_is_live(phase);
    const float w = (ImGui::GetContentRegionAvail().x - 3 * ImGui::GetStyle().ItemSpacing.x) / 4.0f;
    ImGui::BeginDisabled(live || s.ui.welcome_open);
    if (tracked_button(s, "Start", ImVec2(w, 0))) start_run(s);
    ImGui::EndDisabled();
    if (s.ui.welcome_open && ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
        ImGui::SetTooltip("choose an experiment in the welcome first");
    ImGui::SameLine();
    ImGui::BeginDisabled(phase != RunPhase::Running);
    if (tracked_button(s, "Pause", ImVec2(w, 0))) pause_run(s);
    ImGui::EndDisabled();
    ImGui::SameLine();
    // After Stop, Resume goes on from the run's last checkpoint (its folder is known).
    const bool stopped_resumable = !stopped_run_folder(s).empty();
    ImGui::BeginDisabled(phase != RunPhase::Paused && phase != RunPhase::Pausing &&
                         !stopped_resumable);
    if (tracked_button(s, "Resume", ImVec2(w, 0))) {
        if (stopped_resumable)
            resume_stopped_run(s);
        else
            resume_run(s);
    }
    ImGui::EndDisabled();
    if (stopped_resumable && ImGui::IsItemHovered())
        ImGui::SetTooltip("go on from the last checkpoint of %s", stopped_run_folder(s).c_str());
    ImGui::SameLine();
    ImGui::BeginDisabled(!live || phase == RunPhase::Stopping);
    if (tracked_button(s, "Stop", ImVec2(w, 0))) stop_run(s);
    ImGui::EndDisabled();

    // The same fields whether a run is live or not (issue 25 item 7: the panel jumped when a
    // run finished and they came back): while it runs they show its own values, greyed.
    sync_draft(s);
    const bool show_run = live && s.run.snapshot && s.run.snapshot->loaded;
    evo::Evolution run_params = show_run ? s.run.snapshot->experiment.evolution : s.draft.evolution;
    std::string run_dir = show_run ? s.run.snapshot->run_dir : s.run.dir_field;
    auto& ev = live ? run_params : s.draft.evolution;
    ImGui::BeginDisabled(live);
    {
        ImGui::PushItemWidth(ImGui::GetFontSize() * 5.0f);
        ImGui::InputInt("threads", &ev.threads, 0);
        if (!live && ImGui::IsItemDeactivatedAfterEdit()) commit_draft(s, "threads");
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("worker threads; 0 = all hardware threads");
        ImGui::SameLine();
        ImGui::InputScalar("seed", ImGuiDataType_U64, &ev.seed);
        if (!live && ImGui::IsItemDeactivatedAfterEdit()) commit_draft(s, "seed");
        ImGui::InputInt("generations", &ev.generations, 0);
        if (!live && ImGui::IsItemDeactivatedAfterEdit()) commit_draft(s, "generations");
        ImGui::SameLine();
        ImGui::InputDouble("h budget", &ev.wall_budget_h, 0.0, 0.0, "%.3g");
        if (!live && ImGui::IsItemDeactivatedAfterEdit()) commit_draft(s, "wall budget");
        ImGui::PopItemWidth();
        hinted_text_field(s, "##run dir", "run directory (empty: a new folder in the data folder)",
                          live ? run_dir : s.run.dir_field);
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("empty: %s/<name>-<time>", default_runs_root().c_str());
    }
    ImGui::EndDisabled();
    if (!live) {
        // nothing to say: the fields above are the next run's
    } else if (s.run.snapshot && s.run.snapshot->loaded && !s.run.showing_directory &&
               !editing_run_document(s)) {
        // The run owns its experiment: say so, so nobody expects these edits to reach it.
        ImGui::TextDisabled(
            "The editor shows another experiment than the run's: its edits "
            "do not reach the run.");
    } else if (rules_differ_from_run(s)) {
        // What differs, named: the measure is only one of the rules a user may have edited.
        ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(0.75f, 0.45f, 0.0f, 1.0f));
        ImGui::TextWrapped("Edited rules (%s) will apply %s.", describe_rules_to_send(s).c_str(),
                           phase == RunPhase::Paused ? "on Resume" : "after Apply to run");
        ImGui::PopStyleColor();
        record_widget(s, "edited rules");
    }
}

const ImVec4 kErrorRed(0.8f, 0.2f, 0.1f, 1.0f);

// A failed run's message in red, wrapped, and whole on hover (it names files and fields).
void failure_message(Studio& s, const std::string& message) {
    ImGui::PushStyleColor(ImGuiCol_Text, kErrorRed);
    ImGui::TextWrapped("%s", message.c_str());
    ImGui::PopStyleColor();
    record_widget(s, "run failure");
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", message.c_str());
}

// A run that failed before it was built (a resume with no usable checkpoint). The way out comes
// before the message, which names two files and their problems and can be long.
void failure(Studio& s, const EvolutionSnapshot& run) {
    ImGui::TextColored(kErrorRed, "state: failed");
    if (!run.run_dir.empty()) {
        ImGui::SameLine();
        if (tracked_button(s, "Start again from generation 0")) restart_from_run_info(s);
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip(
                "a new run folder, with the experiment this run was started with (its "
                "run.json); the damaged folder is left as it is");
    }
    failure_message(s, run.message);
    if (!run.run_dir.empty()) ImGui::TextDisabled("folder: %s", run.run_dir.c_str());
}

// CalculiX in the loop (evolution.verify): the settings in force, how many bodies were checked
// and how the champion's check came out; settings sent and not yet in force, in orange.
void loop_checks_line(Studio& s, const EvolutionSnapshot& run) {
    const auto& verify = run.experiment.evolution.verify;
    const evo::LoopVerifySettings* sent =
        s.run.showing_directory ? nullptr : s.run.evolution.sent_verify();
    const bool pending = sent && !(*sent == verify) && run_is_live(s.run.evolution.phase());
    if (!verify.enabled() && run.loop_checks.empty() && !pending) return;
    int agree = 0;
    for (const auto& c : run.loop_checks)
        agree += c.outcome == evo::LoopCheckOutcome::Agrees;
    const evo::LoopCheck* champion =
        run.has_champion ? loop_check_of(run, run.champion.id) : nullptr;
    const std::string of_champion =
        !run.has_champion ? ""
        : !champion       ? "; champion not checked"
        : champion->outcome == evo::LoopCheckOutcome::Agrees  ? "; champion agrees"
        : champion->outcome == evo::LoopCheckOutcome::Differs ? "; champion differs"
                                                              : "; champion not compared";
    // Short, so it fits the panel's width in one or two lines; the whole settings on hover.
    char text[160];
    if (verify.enabled())
        std::snprintf(text, sizeof text, "CalculiX every %d gen, top %d, %s: %zu checked, %d agree",
                      verify.every_generations, verify.top_k,
                      evo::kVerifyPolicyNames[static_cast<std::size_t>(verify.policy)],
                      run.loop_checks.size(), agree);
    else
        std::snprintf(text, sizeof text, "CalculiX checks off: %zu checked, %d agree",
                      run.loop_checks.size(), agree);
    ImGui::TextWrapped("%s%s", text, of_champion.c_str());
    record_widget(s, "loop checks");
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip(
            "%s\nthe best bodies not checked before are solved in CalculiX beside the next\n"
            "generation's simulations; their badges are in Analysis > Population and\n"
            "Champions and over the 3D view (docs/verify.md)",
            describe_verify_settings(verify).c_str());
    if (pending) {
        ImGui::TextColored(ImVec4(0.75f, 0.45f, 0.0f, 1.0f), "sent, from the next generation: %s",
                           describe_verify_settings(*sent).c_str());
        record_widget(s, "loop checks pending");
    }
}

void status(Studio& s) {
    const auto& run = s.run.snapshot;
    if (!run || (run->phase == RunPhase::Idle && run->history.empty())) {
        if (s.run.showing_directory && !s.run.directory.error().empty())
            // e.g. a damaged run.json: say which file, rather than "No run yet".
            ImGui::TextColored(kErrorRed, "Cannot show the run: %s",
                               s.run.directory.error().c_str());
        else
            ImGui::TextDisabled("No run yet: Start evolves the current experiment.");
        return;
    }
    if (!run->loaded) {  // a resumed run while its checkpoint loads: no defaults shown as its own
        if (run->phase == RunPhase::Failed) {
            // The load failed (no usable checkpoint): say so, as the CLI does, and offer what
            // the CLI's message proposes, a start from generation 0 in a new folder.
            failure(s, *run);
            return;
        }
        ImGui::TextUnformatted("state: loading the checkpoint");
        if (!run->run_dir.empty()) ImGui::TextDisabled("folder: %s", run->run_dir.c_str());
        return;
    }
    const auto measure = run->experiment.fitness.measure;
    // The session's phase is read live (an atomic), not from the last snapshot: Pause or Stop
    // shows at once.
    const RunPhase phase = s.run.showing_directory ? run->phase : s.run.evolution.phase();
    const LiveProgress& progress = s.run.progress;
    if (ImGui::BeginTable("status", 4, ImGuiTableFlags_SizingStretchProp)) {
        auto cell = [](const char* name, const std::string& value) {
            ImGui::TableNextColumn();
            ImGui::TextDisabled("%s", name);
            ImGui::TableNextColumn();
            ImGui::TextUnformatted(value.c_str());
        };
        char text[64];
        // Live: the generation in progress counts (elapsed, simulations, rate, ETA move inside a
        // generation); a watched directory has only its files.
        const LiveFigures live = s.run.showing_directory ? live_figures(*run, {}, phase)
                                                         : live_figures(*run, progress, phase);
        cell("state", s.run.showing_directory ? "viewing" : run_phase_name(phase));
        std::snprintf(text, sizeof text, "%d / %d", run->generation, run->generation_budget);
        cell("generation", text);
        cell("best", run->has_champion ? format_fitness(run->best_fitness, measure) : "-");
        std::snprintf(text, sizeof text, "%.2f", live.simulations_per_s);
        cell("sims/s", text);
        cell("elapsed", format_duration(live.elapsed_s));
        cell("ETA", live.eta_s >= 0.0 ? format_duration(live.eta_s) : "-");
        std::snprintf(text, sizeof text, "%lld", static_cast<long long>(live.simulations));
        cell("simulations", text);
        cell("measure", evo::kFitnessNames[static_cast<std::size_t>(measure)]);
        cell("algorithm", evo::kAlgorithmNames[static_cast<std::size_t>(
                              run->experiment.evolution.algorithm)]);
        if (run->species > 0) {
            std::snprintf(text, sizeof text, "%d", run->species);
            cell("species", text);
        }
        if (run->novelty) {  // novelty search: how novel, how much remembered
            std::snprintf(text, sizeof text, "%.4g", run->novelty->best_novelty);
            cell("novelty", text);
            std::snprintf(text, sizeof text, "%d", run->novelty->archive_size);
            cell("archive", text);
        }
        ImGui::EndTable();
    }
    loop_checks_line(s, *run);
    if (!s.run.showing_directory && progress.running && run_is_live(phase) &&
        progress.generation >= run->generation) {
        // Per-simulation progress of the generation in progress.
        char text[96];
        const int total = progress.simulations_total;
        if (total > 0)
            std::snprintf(text, sizeof text, "generation %d: simulation %d of %d%s",
                          progress.generation, std::min(total, progress.simulations_done + 1),
                          total, phase == RunPhase::Paused ? " (frozen)" : "");
        else
            std::snprintf(text, sizeof text, "generation %d: making its individuals",
                          progress.generation);
        ImGui::ProgressBar(total > 0 ? float(progress.simulations_done) / float(total) : 0.0f,
                           ImVec2(-1.0f, 0.0f), text);
        record_widget(s, "generation progress");
    } else if (!s.run.showing_directory) {
        // The bar's line stays when no generation is in progress: nothing under it moves.
        ImGui::Dummy(ImVec2(1.0f, ImGui::GetFrameHeight()));
    }
    if (!run->run_dir.empty()) {
        ImGui::TextDisabled("folder: %s", run->run_dir.c_str());
        record_widget(s, "run folder");
    }
    // The message says what the run is doing now: the session's phase moves at once (Pause,
    // Stop), the snapshot's message only when the run thread publishes.
    std::string message = run->message;
    if (!s.run.showing_directory && phase != run->phase) {
        if (phase == RunPhase::Paused)
            message = "paused: the simulations in flight are frozen and go on at Resume";
        else if (phase == RunPhase::Pausing)
            message = "pausing after this generation is saved";
        else if (phase == RunPhase::Stopping)
            message = "stopping: the simulations in flight are aborted";
        else if (phase == RunPhase::Running && run->phase == RunPhase::Paused)
            message = "resumed";
    }
    if (phase == RunPhase::Failed && !s.run.showing_directory) {
        failure_message(s, message);
    } else if (!message.empty()) {
        ImGui::TextWrapped("%s", message.c_str());
    }
}

void run_directory(Studio& s) {
    if (!ImGui::TreeNode("Run directory (bhm evolve)")) return;
    hinted_text_field(s, "##open run", "run directory", s.run.open_field);
    if (tracked_button(s, "Open run...")) show_file_dialog(s, FileDialogPurpose::OpenRun);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("browse for a run directory to view");
    ImGui::SameLine();
    if (tracked_button(s, "Compare...")) show_file_dialog(s, FileDialogPurpose::CompareRun);
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("browse for a run directory whose fitness history to overlay");
    if (tracked_button(s, "View")) open_run_directory(s, s.run.open_field);
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("inspect, plot and replay it; refreshed as it grows");
    ImGui::SameLine();
    if (tracked_button(s, "Resume run")) resume_run_directory(s, s.run.open_field);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("continue it from its last checkpoint");
    ImGui::SameLine();
    if (tracked_button(s, "Compare")) add_compared_run(s, s.run.open_field);
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("overlay its fitness history, thin, on the plots of the same measure");
    for (std::size_t k = 0; k < s.run.compared.size(); ++k) {
        ImGui::PushID(static_cast<int>(k));
        if (ImGui::SmallButton("x")) {
            remove_compared_run(s, k);
            ImGui::PopID();
            break;
        }
        ImGui::SameLine();
        ImGui::TextDisabled("compared: %s", s.run.compared[k].dir.c_str());
        ImGui::PopID();
    }
    if (s.run.showing_directory) {
        ImGui::SameLine();
        if (tracked_button(s, "Close")) close_run_directory(s);
        if (!s.run.directory.error().empty())
            ImGui::TextColored(kErrorRed, "%s", s.run.directory.error().c_str());
    }
    ImGui::TreePop();
}

}  // namespace

void draw_run_panel(Studio& s) {
    controls(s);
    ImGui::Separator();
    status(s);
    run_directory(s);
}

}  // namespace bhm::app::gui
