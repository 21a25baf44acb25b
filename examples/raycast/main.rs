//! The example ray caster: `cargo run --release --example raycast -- SCENE -o OUT.png`.
//! Being written.

#[allow(dead_code)] // until the renderer uses it
mod geometry;
mod parse;
#[allow(dead_code)] // until the renderer uses every field
mod scene;

fn main() {
    let path = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "scenes/showcase.txt".into());
    match parse::parse_file(std::path::Path::new(&path)) {
        Ok(scene) => println!("{} objects", scene.objects.len()),
        Err(e) => {
            eprintln!("{e}");
            std::process::exit(1);
        }
    }
}
