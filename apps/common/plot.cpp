#include "plot.hpp"

#include <cstdlib>
#include <fstream>
#include <system_error>

#include <unistd.h>

#include <fmt/core.h>

#include "cli.hpp"

namespace iris::app {
namespace {

std::string quoted(std::string s) {
    for (char& c : s)
        if (c == '"' || c == '\\') c = '\'';
    return "\"" + s + "\"";
}

}  // namespace

void write_plot(const plot& p, const std::filesystem::path& png) {
    namespace fs = std::filesystem;
    const fs::path parent = png.parent_path().empty() ? fs::path(".") : png.parent_path();
    if (!fs::is_directory(parent))
        throw usage_error(fmt::format("cannot write '{}': directory '{}' does not exist", png.string(), parent.string()));

    static int counter = 0;
    const fs::path work = fs::temp_directory_path() / fmt::format("iris-plot-{}-{}", ::getpid(), counter++);
    fs::create_directories(work);
    const fs::path tmp_png = fs::path(png).concat(fmt::format(".tmp-{}", ::getpid()));
    std::ofstream script(work / "plot.gp");
    script << fmt::format("set terminal pngcairo size {},{} enhanced font 'sans,11'\n", p.width, p.height)
           << "set output " << quoted(tmp_png.string()) << "\n"
           << "set title " << quoted(p.title) << "\nset xlabel " << quoted(p.xlabel) << "\nset ylabel "
           << quoted(p.ylabel) << "\nset grid\nset key outside right top\n"
           << (p.log_x ? "set logscale x 2\n" : "") << (p.log_y ? "set logscale y\n" : "");
    script << "plot ";
    for (std::size_t i = 0; i < p.lines.size(); ++i) {
        const fs::path data = work / fmt::format("series{}.dat", i);
        std::ofstream d(data);
        for (std::size_t k = 0; k < p.lines[i].x.size() && k < p.lines[i].y.size(); ++k)
            d << fmt::format("{:.9g} {:.9g}\n", p.lines[i].x[k], p.lines[i].y[k]);
        script << (i ? ", " : "") << quoted(data.string()) << " using 1:2 with " << (p.points ? "linespoints pt 7 ps 0.8" : "lines") << " lw 2 title "
               << quoted(p.lines[i].title);
    }
    script << "\n";
    script.close();

    const std::string cmd = fmt::format("gnuplot {} 2>{}", quoted((work / "plot.gp").string()),
                                        quoted((work / "gnuplot.log").string()));
    const int status = std::system(cmd.c_str());
    std::error_code ec;
    if (status != 0 || !fs::exists(tmp_png)) {
        std::ifstream log(work / "gnuplot.log");
        std::string first;
        std::getline(log, first);
        fs::remove(tmp_png, ec);
        fs::remove_all(work, ec);
        throw std::runtime_error(fmt::format("gnuplot failed (is gnuplot-nox installed?): {}", first));
    }
    fs::rename(tmp_png, png, ec);
    fs::remove_all(work, ec);
    if (ec) throw usage_error(fmt::format("cannot write '{}': {}", png.string(), ec.message()));
}

}  // namespace iris::app
