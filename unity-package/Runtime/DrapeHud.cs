using System.Text;
using UnityEngine;

namespace Drape
{
    /// <summary>An on-screen overlay with what the paper's app showed: step time, model, backend,
    /// vertex count and parameters. The text is rebuilt a few times per second into a reused
    /// StringBuilder; building the string allocates then, not every frame.</summary>
    [AddComponentMenu("Drape/Drape HUD")]
    public sealed class DrapeHud : MonoBehaviour
    {
        [Tooltip("The cloth to show; the first one in the scene when empty.")]
        public DrapeCloth Cloth;

        [Tooltip("Seconds between text refreshes.")]
        [Range(0.05f, 2f)] public float RefreshInterval = 0.25f;

        [Tooltip("Screen position and size of the panel, pixels.")]
        public Rect Panel = new Rect(10, 10, 320, 170);

        private readonly StringBuilder _text = new StringBuilder(256);
        private string _shown = string.Empty;
        private float _nextRefresh;
        private float _smoothedMs;

        private void Update()
        {
            if (Cloth == null) Cloth = FindObjectOfType<DrapeCloth>();
            if (Cloth == null) return;
            float ms = Cloth.LastStats.StepMs;
            _smoothedMs = _smoothedMs <= 0f ? ms : Mathf.Lerp(_smoothedMs, ms, 0.1f);
            if (Time.unscaledTime < _nextRefresh) return;
            _nextRefresh = Time.unscaledTime + RefreshInterval;
            _text.Length = 0;
            _text.Append("Drape  step ").Append(_smoothedMs.ToString("F2")).Append(" ms\n");
            _text.Append("model ").Append(Cloth.Model.ToString()).Append("  backend ").Append(Cloth.ActiveBackend.ToString()).Append('\n');
            _text.Append("vertices ").Append(Cloth.VertexCount).Append('\n');
            _text.Append("substeps ").Append(Cloth.LastStats.Substeps).Append("  iterations ").Append(Cloth.LastStats.Iterations).Append('\n');
            _text.Append("stiffness ").Append(Cloth.StructuralStiffness).Append(" / ").Append(Cloth.ShearStiffness)
                 .Append(" / ").Append(Cloth.BendStiffness).Append('\n');
            _text.Append("damping ").Append(Cloth.Damping).Append("  mass ").Append(Cloth.TotalMass).Append(" kg\n");
            _text.Append("max strain ").Append((Cloth.LastStats.MaxStrain * 100f).ToString("F1")).Append(" %");
            if (Cloth.IsAsleep) _text.Append("  (asleep)");
            _shown = _text.ToString();
        }

        private void OnGUI()
        {
            GUI.Box(Panel, GUIContent.none);
            GUI.Label(new Rect(Panel.x + 8, Panel.y + 6, Panel.width - 16, Panel.height - 12), _shown);
        }
    }
}
